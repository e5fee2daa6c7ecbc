"""One LeRobot control loop at a fixed rate, on LeRobot 0.6.1's own robot API: each iteration
`robot.get_observation()` then `robot.send_action()`, paced as LeRobot's teleoperate and record
loops pace themselves (precise_sleep of what is left of 1/fps). The robot is either LeRobot's
own SO101Follower on a serial port (its FeetechMotorsBus straight on the emulated bus) or
armtwin's plugin (`--robot.type=armtwin`, found by register_third_party_plugins) on MQTT.

The action moves shoulder_pan in a triangle wave of `step` degrees an iteration (every other
motor held where it started), so each action's goal is distinct. While the loop waits for its
next iteration it keeps reading `get_observation()` (`probe_ms` apart), so the time a goal is
first reported is known to a few ms rather than to a loop period. Its one argument is JSON:
  {"mode": "direct"|"armtwin", "fps", "seconds", "step", "amplitude", "tolerance", "probe_ms",
   "window_s", "settle",
   "port", "calibration_dir" (direct), "broker", "arm" (armtwin)}
and prints JSON: {"iterations", "overruns", "late_ms": [...], "latency_ms": [...], "unreached",
"read_errors", "scored"} (latency: action sent -> first observation at its goal or past it)."""

import json
import sys
import time
from pathlib import Path

import lerobot.motors.feetech.feetech
from lerobot.motors import MotorCalibration
from lerobot.utils.robot_utils import precise_sleep

MOTORS = ("shoulder_pan", "shoulder_lift", "elbow_flex", "wrist_flex", "wrist_roll", "gripper")
PAN = "shoulder_pan.pos"


def patient_packet_timeout(self, packet_length):
    """LeRobot's per-packet reply allowance (its patch of the servo SDK, 50 ms) at 500 ms: the
    emulated bus (node on a pty) answers late on a loaded machine, as in lerobot-plugin.test.ts."""
    self.packet_start_time = self.getCurrentTime()
    self.packet_timeout = self.tx_time_per_byte * (packet_length + 3.0) + 500


def answers(bus, motor):
    try:
        return bus.ping(motor) is not None
    except IndexError:  # the servo SDK's ping on a reply cut short
        return False


def direct_robot(req):
    from lerobot.robots.so_follower import SO101Follower, SO101FollowerConfig

    lerobot.motors.feetech.feetech.patch_setPacketTimeout = patient_packet_timeout
    cfg = SO101FollowerConfig(port=req["port"], id="bench", calibration_dir=Path(req["calibration_dir"]))
    robot = SO101Follower(cfg)
    # A full turn each, zero homing: LeRobot's degrees 0 at mid-turn, where the emulated bus
    # puts the SO-101's home pose (tick 2048).
    robot.calibration = {
        m: MotorCalibration(id=i + 1, drive_mode=0, homing_offset=0, range_min=0, range_max=4095)
        for i, m in enumerate(MOTORS)
    }
    robot._save_calibration()
    # A fresh emulated bus can miss the first packets while node warms up on a loaded machine;
    # wait until every servo answers LeRobot's own ping (30 s at most), then let it connect.
    robot.bus.connect(handshake=False)
    deadline = time.monotonic() + 30
    while not all(answers(robot.bus, m) for m in robot.bus.motors) and time.monotonic() < deadline:
        time.sleep(0.2)
    robot.bus.disconnect(disable_torque=False)
    robot.connect(calibrate=False)
    robot.bus.write_calibration(robot.calibration)
    return robot


def armtwin_robot(req):
    from lerobot.robots import RobotConfig, make_robot_from_config
    from lerobot.utils.import_utils import register_third_party_plugins

    register_third_party_plugins()
    cfg = RobotConfig.get_choice_class("armtwin")(broker=req["broker"], arm=req["arm"], user="bench")
    robot = make_robot_from_config(cfg)
    robot.connect()
    return robot


def run(robot, req):
    fps, step, amp, tol = req["fps"], req["step"], req["amplitude"], req["tolerance"]
    period = 1.0 / fps
    probe_s = req["probe_ms"] / 1000.0
    window = req["window_s"]
    n = int(req["seconds"] * fps)
    first = robot.get_observation()
    hold = {f"{m}.pos": float(first[f"{m}.pos"]) for m in MOTORS}
    centre = hold[PAN]
    sent = []  # (time, goal, direction, iterations since the wave turned)
    seen = []  # (time, shoulder_pan)
    overruns, late_ms, errors = 0, [], 0
    offset = 0.0
    direction = 1.0
    since_turn = 0
    for i in range(n):
        start = time.perf_counter()
        try:
            obs = robot.get_observation()
            seen.append((time.perf_counter(), float(obs[PAN])))
        except (ConnectionError, RuntimeError):
            errors += 1
        since_turn += 1
        if abs(offset + direction * step) > amp:
            direction = -direction
            since_turn = 0
        offset += direction * step
        goal = round(centre + offset, 3)
        action = dict(hold, **{PAN: goal})
        t = time.perf_counter()
        robot.send_action(action)
        sent.append((t, goal, direction, since_turn))
        dt = time.perf_counter() - start
        if dt > period:
            overruns += 1
            late_ms.append((dt - period) * 1000)
        # What is left of the period: LeRobot sleeps it; the probe reads in it, and stops in time.
        deadline = start + period
        while True:
            left = deadline - time.perf_counter()
            if left <= probe_s * 2:
                break
            precise_sleep(probe_s)
            try:
                seen.append((time.perf_counter(), float(robot.get_observation()[PAN])))
            except (ConnectionError, RuntimeError):
                errors += 1
        precise_sleep(max(deadline - time.perf_counter(), 0.0))
    latency, unreached, scored = latencies(sent, seen, tol, window, req["settle"])
    return {
        "iterations": n,
        "overruns": overruns,
        "late_ms": late_ms,
        "latency_ms": latency,
        "unreached": unreached,
        "scored": scored,
        "read_errors": errors,
        "observations": len(seen),
    }


def latencies(sent, seen, tol, window, settle):
    """Action sent -> the first observation at its goal or past it (the wave's way, within `tol`),
    ms. The first `settle` actions after the wave turns are not scored (a report from before the
    turn could pass for theirs); a goal not reached within `window` s is unreached (goals in
    flight at the end are left out). Returns (latencies, unreached, scored)."""
    end = seen[-1][0] if seen else 0
    out, unreached, scored = [], 0, 0
    j = 0
    for t, goal, direction, since_turn in sent:
        while j < len(seen) and seen[j][0] < t:
            j += 1
        if since_turn < settle:
            continue
        hit = next((s for s in seen[j:] if s[0] - t <= window and direction * (s[1] - goal) >= -tol), None)
        if hit is not None:
            out.append((hit[0] - t) * 1000)
            scored += 1
        elif end - t > window:
            unreached += 1
            scored += 1
    return out, unreached, scored


def main():
    req = json.loads(sys.argv[1])
    robot = direct_robot(req) if req["mode"] == "direct" else armtwin_robot(req)
    try:
        print("ready", file=sys.stderr, flush=True)
        out = run(robot, req)
    finally:
        robot.disconnect()
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main()
