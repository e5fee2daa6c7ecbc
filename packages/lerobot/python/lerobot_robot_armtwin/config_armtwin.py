"""The settings of an arm driven through armtwin (`--robot.type=armtwin --robot.arm=so101 …`)."""

from dataclasses import dataclass, field

from lerobot.cameras import CameraConfig
from lerobot.robots.config import RobotConfig


@dataclass
class ArmtwinCameraConfig:
    """An armtwin camera's picture size (LeRobot's features are declared before connecting)."""

    width: int = 640
    height: int = 480


@RobotConfig.register_subclass("armtwin")
@dataclass
class ArmtwinConfig(RobotConfig):
    # The broker armtwin's controller (armtwin sim, armtwin gateway) is on.
    broker: str = "mqtt://localhost:1883"
    # The arm's id (arm/{arm}/…).
    arm: str = "so101"
    # Who LeRobot is to armtwin: commands go on arm/{arm}/control/{user}, claims on …/claim/{user}.
    user: str = "lerobot"
    username: str | None = None
    password: str | None = None
    # Each action's move time, ms (0: as fast as the servos go; the controller still limits speed).
    move_ms: int = 0
    # As LeRobot's SO follower: the most a joint's goal may be from where it is, per action.
    max_relative_target: float | dict[str, float] | None = None
    # How long connect() waits for the broker, the arm's profile, its first position and the lease.
    connect_timeout_s: float = 10.0
    # LeRobot's own cameras (opened by LeRobot on this machine).
    cameras: dict[str, CameraConfig] = field(default_factory=dict)
    # armtwin's cameras of the arm, by name (`armtwin camera --name front --arm so101`): read from
    # the MJPEG stream its announcement on arm/{arm}/camera/{name} gives, observed as
    # observation.images.{name}: `--robot.armtwin_cameras='{front: {width: 640, height: 480}}'`.
    armtwin_cameras: dict[str, ArmtwinCameraConfig] = field(default_factory=dict)
    # An armtwin camera picture older than this is an error in get_observation (a stalled stream).
    camera_max_age_s: float = 1.0
