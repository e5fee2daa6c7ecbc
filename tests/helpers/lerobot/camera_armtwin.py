"""armtwin's camera streams in the LeRobot plugin's observations: the robot made by LeRobot 0.6.1's
own code (register_third_party_plugins, make_robot_from_config) from the command-line form of its
config (`--armtwin_cameras='{front: {width: 640, height: 480}}'`, parsed by draccus as LeRobot
parses it), connected, then observed `n` times `interval_s` apart.
Reads JSON on stdin: {"broker", "arm", "user", "camera", "width", "height", "n", "interval_s"}.
Prints JSON: {"features": LeRobot's dataset features of the observation {key: shape},
"images": [{"shape", "dtype", "red": base64 of the picture's red channel}], "positions": [...]}."""
import base64
import json
import sys
import time

import draccus

from lerobot.robots import RobotConfig
from lerobot.robots.utils import make_robot_from_config
from lerobot.utils.feature_utils import hw_to_dataset_features
from lerobot.utils.import_utils import register_third_party_plugins

req = json.load(sys.stdin)
register_third_party_plugins()  # LeRobot's own discovery: imports lerobot_robot_armtwin
cam = req["camera"]
cfg = draccus.parse(
    RobotConfig.get_choice_class("armtwin"),
    args=[
        f"--broker={req['broker']}",
        f"--arm={req['arm']}",
        f"--user={req['user']}",
        f"--armtwin_cameras={{{cam}: {{width: {req['width']}, height: {req['height']}}}}}",
    ],
)
robot = make_robot_from_config(cfg)
features = hw_to_dataset_features(robot.observation_features, "observation")
robot.connect()
images, positions = [], []
try:
    for i in range(req["n"]):
        if i:
            time.sleep(req["interval_s"])
        obs = robot.get_observation()
        img = obs[cam]
        images.append(
            {
                "shape": list(img.shape),
                "dtype": str(img.dtype),
                "red": base64.b64encode(img[:, :, 0].tobytes()).decode(),
            }
        )
        positions.append(obs["shoulder_pan.pos"])
finally:
    robot.disconnect()
print(json.dumps({"features": {k: list(v["shape"]) for k, v in features.items()}, "images": images, "positions": positions}))
