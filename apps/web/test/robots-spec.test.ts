/**
 * Profile → what the HUD needs (src/core/robots/robotSpec.ts): the store's arm, the jog sliders and
 * the servo → URDF joint map, for armtwin5 (must equal the HUD's old hard-wired DEMO_ARM
 * behaviour) and track6 (7 axes, a prismatic track, an offset, a −1 polarity). The joint map
 * is checked end to end: URDF joints set through it (urdf-loader) put track6's `tcp` link where
 * the planner's FK says the tip is.
 */
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { beforeAll, describe, expect, it } from 'vitest';
import * as THREE from 'three';
import type { URDFRobot } from 'urdf-loader';
import { parseUrdf } from './support/parseUrdf.ts';
import { DEMO_ARM } from '@armtwin/ik';
import { chainFromUrdf, parseProfile, type Profile } from '@armtwin/robot';
import { createMotionRobot, tipPose } from '@armtwin/motion';
import { angleFromPwm, pwmFromAngle } from '@armtwin/protocol';
import { robotSpec, sliderSpecs, storeArmFor } from '../src/core/robots/robotSpec.ts';
import { DEFAULT_PROFILE } from '../src/core/robots/defaultProfile.ts';

const MODELS = path.resolve(fileURLToPath(import.meta.url), '../../../../public/models');
const read = (name: string, file: string) => fs.readFileSync(path.join(MODELS, name, file), 'utf8');
function profile(name: string): Profile {
  const r = parseProfile(JSON.parse(read(name, 'profile.json')));
  if (!r.ok) throw new Error(r.errors.join('; '));
  return r.profile;
}
const ARMTWIN5 = profile('armtwin5');
const TRACK6 = profile('track6');
const DEG = Math.PI / 180;

describe('armtwin5: the HUD as before', () => {
  it('the bundled default is armtwin5, and its store arm is DEMO_ARM', () => {
    expect(DEFAULT_PROFILE).toEqual(ARMTWIN5);
    expect(storeArmFor(ARMTWIN5)).toEqual(DEMO_ARM);
  });

  it('sliders: names, degree limits and pulses of DEMO_ARM', () => {
    const sliders = sliderSpecs(ARMTWIN5);
    expect(sliders.map((s) => s.name)).toEqual(DEMO_ARM.servos.map((s) => s.name));
    sliders.forEach((s, i) => {
      const d = DEMO_ARM.servos[i]!;
      expect([s.unit, s.min, s.max, s.step]).toEqual(['deg', d.minDeg, d.maxDeg, 1]);
      for (const v of [d.minDeg, -17, 0, 45, d.maxDeg]) {
        expect(s.pwmFromValue(v)).toBe(pwmFromAngle(v, d.polarity));
        const p = pwmFromAngle(v, d.polarity);
        expect(s.valueFromPwm(p)).toBeCloseTo(angleFromPwm(p, d.polarity), 12);
      }
    });
  });

  it('joint map: one store degree is one URDF degree', () => {
    const { joints } = robotSpec(ARMTWIN5);
    expect(joints.names).toEqual([
      'base_yaw',
      'shoulder',
      'elbow',
      'wrist_pitch',
      'wrist_roll',
      'gripper',
    ]);
    for (let i = 0; i < 6; i++) {
      expect(joints.scale[i]).toBeCloseTo(DEG, 15);
      expect(joints.bias[i]).toBeCloseTo(0, 15);
    }
  });
});

describe('track6', () => {
  const spec = robotSpec(TRACK6);
  const value = (i: number, angle: number) => spec.joints.scale[i]! * angle + spec.joints.bias[i]!;

  it('sliders: the track in mm (0–3000, 5 mm steps), the rest in joint degrees', () => {
    const [track, , a2, a3] = spec.sliders;
    expect(spec.sliders.map((s) => s.name)).toEqual([
      'Track',
      'A1 column',
      'A2 upper arm',
      'A3 forearm',
      'A4 forearm roll',
      'A5 wrist',
      'A6 flange',
    ]);
    expect([track!.unit, track!.min, track!.max, track!.step]).toEqual(['mm', 0, 3000, 5]);
    expect(track!.pwmFromValue(0)).toBe(500);
    expect(track!.pwmFromValue(1500)).toBe(1500);
    expect(track!.pwmFromValue(3000)).toBe(2500);
    expect(track!.valueFromPwm(2000)).toBeCloseTo(2250, 9);
    // A3: joint = servo + 15°, so joint 60° is servo angle 45°.
    expect([a3!.min, a3!.max]).toEqual([-115, 145]);
    expect(a3!.pwmFromValue(60)).toBe(pwmFromAngle(45, 1));
    expect(a3!.valueFromPwm(pwmFromAngle(45, 1))).toBeCloseTo(
      angleFromPwm(pwmFromAngle(45, 1)) + 15,
      12,
    );
    // A2: polarity −1, a higher pulse is a lower joint angle.
    expect(a2!.pwmFromValue(30)).toBe(pwmFromAngle(30, -1));
    expect(a2!.pwmFromValue(30)).toBeLessThan(1500);
  });

  it('store arm: pulse-equivalent (polarity +1, the pulse limits as §2 angles)', () => {
    const arm = spec.storeArm;
    expect(arm.servos).toHaveLength(7);
    expect(arm.servos.every((s) => s.polarity === 1)).toBe(true);
    expect(arm.servos[0]!.minDeg).toBeCloseTo(angleFromPwm(500), 9);
    expect(arm.servos[0]!.maxDeg).toBeCloseTo(angleFromPwm(2500), 9);
  });

  it('joint map: store angle → metres on the track, radians (offset, polarity) elsewhere', () => {
    expect(spec.joints.names).toEqual(['track', 'a1', 'a2', 'a3', 'a4', 'a5', 'a6']);
    expect(value(0, angleFromPwm(500))).toBeCloseTo(0, 12);
    expect(value(0, angleFromPwm(1500))).toBeCloseTo(1.5, 12);
    expect(value(0, angleFromPwm(2500))).toBeCloseTo(3, 12);
    // Exact pulses (the store's angles are not rounded): A3 at servo 45° is joint 60°.
    expect(value(3, 45)).toBeCloseTo(60 * DEG, 12);
    // A2 (polarity −1): the pulse of joint 30° is below centre; its store angle maps back to 30°.
    expect(value(2, angleFromPwm(1500 - (30 * 2000) / 270))).toBeCloseTo(30 * DEG, 12);
  });

  describe('through urdf-loader: the drawn tcp is where the planner puts the tip', () => {
    let robot: URDFRobot;
    beforeAll(() => {
      robot = parseUrdf(read('track6', 'track6.urdf'));
    });

    it('for 200 random pulse vectors within the limits, within 0.01 mm', () => {
      const chain = chainFromUrdf(TRACK6, read('track6', 'track6.urdf'));
      if (!chain.ok) throw new Error(chain.errors.join('; '));
      const motion = createMotionRobot(TRACK6, chain.chain);
      let seed = 7;
      const rnd = () => (seed = (seed * 16807) % 2147483647) / 2147483647;
      const tcp = new THREE.Vector3();
      for (let n = 0; n < 200; n++) {
        // Inside the pulse limits by 1 µs: the outermost pulse can be a few hundredths of a
        // degree past the URDF limit (rounding), where urdf-loader clamps the joint.
        const pwm = motion.table.map((s) =>
          Math.round(s.minPwm + 1 + rnd() * (s.maxPwm - s.minPwm - 2)),
        );
        pwm.forEach((p, i) => {
          const angle = angleFromPwm(p, spec.storeArm.servos[i]!.polarity);
          robot.joints[spec.joints.names[i]!]!.setJointValue(value(i, angle));
        });
        robot.updateMatrixWorld(true);
        spec.joints.names.forEach((name, i) =>
          expect(robot.joints[name]!.angle, `${name} ${pwm[i]}`).toBeCloseTo(
            value(i, angleFromPwm(pwm[i]!, spec.storeArm.servos[i]!.polarity)),
            9,
          ),
        );
        robot.links.tcp!.getWorldPosition(tcp).multiplyScalar(1000);
        const tip = tipPose(motion, pwm);
        expect(Math.hypot(tcp.x - tip.x, tcp.y - tip.y, tcp.z - tip.z)).toBeLessThan(0.01);
      }
    });
  });
});
