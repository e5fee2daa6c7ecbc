"""LeRobot's own calibration file functions (lerobot 0.6.1, an SO-101 follower's
Robot._save_calibration / _load_calibration), for the round-trip test. Reads JSON on stdin:
  {"op": "write", "dir": D, "id": ID, "calibration": {motor: {id, drive_mode, ...}}}
      -> LeRobot writes D/ID.json; prints {"path": ...}
  {"op": "read", "path": P} -> LeRobot loads P; prints {motor: {...}} as it read it."""
import dataclasses
import json
import sys
from pathlib import Path

from lerobot.motors import MotorCalibration
from lerobot.robots.so_follower import SO101Follower, SO101FollowerConfig

req = json.load(sys.stdin)
if req["op"] == "write":
    robot = SO101Follower(SO101FollowerConfig(port="/dev/null", id=req["id"], calibration_dir=Path(req["dir"])))
    robot.calibration = {m: MotorCalibration(**c) for m, c in req["calibration"].items()}
    robot._save_calibration()
    json.dump({"path": str(robot.calibration_fpath)}, sys.stdout)
else:
    path = Path(req["path"])
    robot = SO101Follower(SO101FollowerConfig(port="/dev/null", id=path.stem, calibration_dir=path.parent))
    robot._load_calibration(path)
    json.dump({m: dataclasses.asdict(c) for m, c in robot.calibration.items()}, sys.stdout)
