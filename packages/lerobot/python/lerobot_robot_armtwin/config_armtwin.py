"""The settings of an arm driven through armtwin (`--robot.type=armtwin --robot.arm=so101 …`)."""

from dataclasses import dataclass, field

from lerobot.cameras import CameraConfig
from lerobot.robots.config import RobotConfig


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
    cameras: dict[str, CameraConfig] = field(default_factory=dict)
