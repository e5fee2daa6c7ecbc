"""armtwin as a LeRobot robot: `--robot.type=armtwin`. LeRobot's register_third_party_plugins()
imports this package, which registers the config; the robot class sits beside it, where
make_device_from_device_class finds it (ArmtwinConfig -> Armtwin)."""

from .config_armtwin import ArmtwinConfig
from .armtwin import Armtwin

__all__ = ["Armtwin", "ArmtwinConfig"]
