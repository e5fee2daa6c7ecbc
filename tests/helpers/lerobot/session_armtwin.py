"""LeRobot 0.6.1's own teleoperate or record command driving armtwin's robot plugin
(`--robot.type=armtwin`, found by LeRobot's register_third_party_plugins), with LeRobot's
SO-101 leader (so101_leader, FeetechMotorsBus) on an emulated Feetech bus as the teleoperator.
Reads JSON on stdin:
  {"op": "teleoperate"|"record", "broker", "arm", "user", "leader_port", "leader_calibration":
   {motor: {id, drive_mode, homing_offset, range_min, range_max}}, "dir", "fps", "time_s",
   "max_relative_target"}
and prints JSON: {} for "teleoperate"; {"frames": n, "state": [...], "action": [...]} (the
last recorded frame) for "record". The plugin logs refusals and e-stops on stderr."""
import dataclasses
import json
import sys
import time
from pathlib import Path

import lerobot.motors.feetech.feetech

from lerobot.motors import MotorCalibration
from lerobot.robots import RobotConfig
from lerobot.teleoperators.so_leader import SO101Leader, SO101LeaderConfig
from lerobot.utils.import_utils import register_third_party_plugins

req = json.load(sys.stdin)
register_third_party_plugins()  # LeRobot's own discovery: imports lerobot_robot_armtwin
robot_cfg = RobotConfig.get_choice_class("armtwin")(
    broker=req["broker"], arm=req["arm"], user=req["user"], max_relative_target=req.get("max_relative_target")
)
calibration_dir = Path(req["dir"]) / "calibration"
# The emulated bus (node on a pty) answers late on a loaded machine: LeRobot's own per-packet
# reply allowance (its patch of the servo SDK: 50 ms) raised to 500 ms, and LeRobot's own retries
# of a failed sync read. Nothing else of LeRobot's bus is changed.


def patient_packet_timeout(self, packet_length):
    self.packet_start_time = self.getCurrentTime()
    self.packet_timeout = self.tx_time_per_byte * (packet_length + 3.0) + 500


lerobot.motors.feetech.feetech.patch_setPacketTimeout = patient_packet_timeout
teleop_cfg = SO101LeaderConfig(
    port=req["leader_port"], id="leader", calibration_dir=calibration_dir, num_read_retries=10
)
leader = SO101Leader(teleop_cfg)  # writes the leader's calibration file as LeRobot does
leader.calibration = {m: MotorCalibration(**c) for m, c in req["leader_calibration"].items()}
leader._save_calibration()
# A fresh emulated bus can miss the first pings while node warms up; LeRobot's connect pings each
# id once. Wait until every servo answers LeRobot's own ping (20 s at most), then let it connect.


def answers(motor: str) -> bool:
    try:
        return leader.bus.ping(motor) is not None
    except IndexError:  # the servo SDK's ping on a reply cut short
        return False


leader.bus.connect(handshake=False)
deadline = time.monotonic() + 20
while not all(answers(m) for m in leader.bus.motors) and time.monotonic() < deadline:
    time.sleep(0.2)
leader.bus.disconnect(disable_torque=False)

out = {}
if req["op"] == "teleoperate":
    from lerobot.scripts import lerobot_teleoperate as tele

    tele.teleoperate(
        tele.TeleoperateConfig(teleop=teleop_cfg, robot=robot_cfg, fps=req["fps"], teleop_time_s=req["time_s"])
    )
else:
    from lerobot.datasets.lerobot_dataset import LeRobotDataset
    from lerobot.scripts import lerobot_record as rec

    root = Path(req["dir"]) / "dataset"
    rec.record(
        rec.RecordConfig(
            robot=robot_cfg,
            teleop=teleop_cfg,
            dataset=rec.DatasetRecordConfig(
                repo_id="local/armtwin-so101",
                single_task="follow the leader through armtwin",
                root=root,
                fps=req["fps"],
                episode_time_s=req["time_s"],
                reset_time_s=0,
                num_episodes=1,
                video=False,
                push_to_hub=False,
                no_stamp=True,
            ),
            play_sounds=False,
        )
    )
    ds = LeRobotDataset("local/armtwin-so101", root=root)
    last = ds[len(ds) - 1]
    out.update(frames=len(ds), state=last["observation.state"].tolist(), action=last["action"].tolist())

json.dump(out, sys.stdout)
