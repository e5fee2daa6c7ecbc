import { describe, expect, it } from 'vitest';
import * as THREE from 'three';
import { isSoftwareRenderer } from '../src/scene/webglInfo.ts';
import { floorLook } from '../src/scene/stage.ts';

describe('isSoftwareRenderer', () => {
  it('names CPU rasterizers and nothing else', () => {
    expect(
      isSoftwareRenderer(
        'ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device (Subzero) (0x0000C0DE)), SwiftShader driver)',
      ),
    ).toBe(true);
    expect(isSoftwareRenderer('llvmpipe (LLVM 15.0.6, 256 bits)')).toBe(true);
    expect(
      isSoftwareRenderer('ANGLE (NVIDIA, NVIDIA GeForce RTX 3060 Direct3D11 vs_5_0 ps_5_0)'),
    ).toBe(false);
    expect(isSoftwareRenderer('Apple M2')).toBe(false);
  });
});

describe('floorLook', () => {
  it('lights a matte floor as Lambert does, and shades it by the blocked light', () => {
    const white = new THREE.Color(1, 1, 1);
    const look = floorLook(new THREE.Color(0.5, 0.5, 0.5), [{ colour: white, intensity: Math.PI }]);
    expect(look.lit.r).toBeCloseTo(0.5, 6);
    expect(look.shadowOpacity(0)).toBe(0);
    expect(look.shadowOpacity(Math.PI)).toBe(1);
    const half = look.shadowOpacity(Math.PI / 2);
    expect(half).toBeGreaterThan(0);
    expect(half).toBeLessThan(1);
  });
});
