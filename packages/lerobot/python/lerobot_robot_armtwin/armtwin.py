"""An arm driven through armtwin, as a LeRobot Robot: actions become the contract's angle moves
on the user's control topic, so armtwin's controller checks each against the joint limits and
keep-out zones and the lease, and an emergency stop wins over LeRobot; observations are the
positions the arm reports on MQTT, the pictures of armtwin's cameras of the arm (configured by name:
their MJPEG streams, as their announcements give them) and LeRobot's own cameras, if configured."""

import logging
from functools import cached_property

from lerobot.cameras import make_cameras_from_configs
from lerobot.robots.robot import Robot
from lerobot.robots.utils import ensure_safe_goal_position

from . import frames
from .camera_stream import CameraStream
from .config_armtwin import ArmtwinConfig
from .link import ArmLink

logger = logging.getLogger(__name__)

# The SO-101's motors, for the features LeRobot asks for before connecting; connect() checks
# the arm's profile names the same motors.
SO101_MOTORS = ("shoulder_pan", "shoulder_lift", "elbow_flex", "wrist_flex", "wrist_roll", "gripper")


class Armtwin(Robot):
    config_class = ArmtwinConfig
    name = "armtwin"

    def __init__(self, config: ArmtwinConfig):
        super().__init__(config)
        self.config = config
        self.cameras = make_cameras_from_configs(config.cameras)
        both = set(config.cameras) & set(config.armtwin_cameras)
        if both:
            raise ValueError(f"camera names {sorted(both)} are both LeRobot's and armtwin's: rename one")
        self.link: ArmLink | None = None
        self.armtwin_cameras: dict[str, CameraStream] = {}

    @cached_property
    def observation_features(self) -> dict:
        cams = {c: (cam.height, cam.width, 3) for c, cam in self.config.cameras.items()}
        ours = {c: (cam.height, cam.width, 3) for c, cam in self.config.armtwin_cameras.items()}
        return {**self.action_features, **cams, **ours}

    @cached_property
    def action_features(self) -> dict:
        return {f"{m}.pos": float for m in SO101_MOTORS}

    @property
    def is_connected(self) -> bool:
        return self.link is not None and all(c.is_connected for c in self.cameras.values())

    @property
    def is_calibrated(self) -> bool:
        return True  # armtwin's profile holds the calibration (`armtwin robot calibration import`)

    def calibrate(self) -> None:
        pass

    def configure(self) -> None:
        pass

    def connect(self, calibrate: bool = True) -> None:
        if self.link is not None:
            raise ConnectionError(f"{self} is already connected")
        c = self.config
        link = ArmLink(c.broker, c.arm, c.user, c.username, c.password, tuple(c.armtwin_cameras))
        try:
            link.take(c.connect_timeout_s)
            names = tuple(m.name for m in link.motors)
            if names != SO101_MOTORS:
                raise ValueError(f"armtwin arm {c.arm!r} has servos {names}, not an SO-101's {SO101_MOTORS}")
            self._open_armtwin_cameras(link)
        except BaseException:
            self._close_armtwin_cameras()
            link.close()
            raise
        self.link = link
        for cam in self.cameras.values():
            cam.connect()
        logger.info("%s connected to armtwin arm %s as %s", self, c.arm, c.user)

    def _open_armtwin_cameras(self, link: ArmLink) -> None:
        """Each armtwin camera's stream, from its announcement; returns once each gave a picture."""
        c = self.config
        for name, cam in c.armtwin_cameras.items():
            link.wait(
                f"announcement of camera {name!r} on arm/{c.arm}/camera/{name} (is `armtwin camera` running?)",
                lambda n=name: n in link.camera_urls,
                c.connect_timeout_s,
            )
            with link.lock:
                url = link.camera_urls[name]
            stream = CameraStream(name, url, cam.width, cam.height, c.username, c.password)
            self.armtwin_cameras[name] = stream
            stream.start(c.connect_timeout_s)

    def _close_armtwin_cameras(self) -> None:
        for stream in self.armtwin_cameras.values():
            stream.stop()
        self.armtwin_cameras = {}

    def _present(self) -> dict[str, float]:
        link = self._connected()
        with link.lock:
            return {f"{m.name}.pos": frames.to_lerobot(m, link.present[m.id]) for m in link.motors}

    def _connected(self) -> ArmLink:
        if self.link is None:
            raise ConnectionError(f"{self} is not connected")
        return self.link

    def get_observation(self) -> dict:
        obs = self._present()
        for key, cam in self.cameras.items():
            obs[key] = cam.read_latest()
        for key, stream in self.armtwin_cameras.items():
            obs[key] = stream.read_latest(self.config.camera_max_age_s)
        return obs

    def send_action(self, action: dict) -> dict:
        """Sends the goals as one group; returns what was sent (nothing moves after an e-stop: then the present positions)."""
        link = self._connected()
        with link.lock:
            estop, holder, held = link.estop, link.holder, link.held
        if held and holder != link.user:
            raise ConnectionError(f"armtwin arm {link.arm!r}: control passed to {holder}")
        if estop:
            return self._present()
        goals = {k: float(v) for k, v in action.items() if k.endswith(".pos")}
        limit = self.config.max_relative_target
        if limit is not None:
            present = self._present()
            goals = ensure_safe_goal_position(  # LeRobot's own clamp, which takes floats only
                {k.removesuffix(".pos"): (g, present[k]) for k, g in goals.items()},
                float(limit) if isinstance(limit, int) else limit,
            )
            goals = {f"{k}.pos": v for k, v in goals.items()}
        by_name = {m.name: m for m in link.motors}
        moves = [(by_name[k.removesuffix(".pos")], g) for k, g in goals.items()]
        link.move(frames.move_group([(m, frames.to_degrees(m, g)) for m, g in moves], self.config.move_ms))
        return goals

    def disconnect(self) -> None:
        link = self._connected()
        self.link = None
        link.close()
        self._close_armtwin_cameras()
        for cam in self.cameras.values():
            cam.disconnect()
        logger.info("%s disconnected (refused: %s)", self, dict(link.refused))
