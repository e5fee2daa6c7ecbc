"""The plugin's MQTT side (paho-mqtt): the arm's profile, positions, holder record and audit in;
claims, beats and moves out, on the user's own topics (docs/protocol.md § Control). Everything
it hears is kept under a lock for the robot's thread; what it cannot read is counted by kind."""

import logging
import threading
import time
from collections import Counter
from urllib.parse import urlparse

import paho.mqtt.client as mqtt

from . import frames, mjpeg

logger = logging.getLogger(__name__)
BEAT_S = 0.5  # the HUD's beat: a holder that stops beating loses the arm after the lease


def broker_address(url: str) -> tuple[str, int]:
    """host and port of an mqtt:// (or tcp://) URL."""
    u = urlparse(url)
    if u.scheme not in ("mqtt", "tcp") or not u.hostname:
        raise ValueError(f"broker {url!r}: use mqtt://host:port")
    return u.hostname, u.port or 1883


class ArmLink:
    def __init__(
        self, broker: str, arm: str, user: str, username: str | None, password: str | None, cameras: tuple[str, ...] = ()
    ):
        self.arm, self.user = arm, user
        self.topics = {
            s: f"arm/{arm}/{s}" for s in ("status", "profile", "holder", "audit")
        }
        # The announcements of armtwin's cameras to observe: their MJPEG stream URLs, by name.
        self.camera_topics = {f"arm/{arm}/camera/{name}": name for name in cameras}
        self.camera_urls: dict[str, str] = {}
        self.control = f"arm/{arm}/control/{user}"
        self.claim = f"arm/{arm}/claim/{user}"
        self.lock = threading.Lock()
        self.changed = threading.Condition(self.lock)
        self.motors: list[frames.Motor] = []
        self.present: dict[int, float] = {}
        self.holder: str | None = None
        self.held = False
        self.estop: str | None = None  # the audit detail of an e-stop seen while connected
        self.refused = Counter()  # the controller's refusals of our commands, by kind
        self.rejected = Counter()  # what came in unreadable, by kind
        self.last_error = ""
        self._beating = threading.Event()
        host, port = broker_address(broker)
        self.client = mqtt.Client(mqtt.CallbackAPIVersion.VERSION2, client_id=f"lerobot-{arm}-{user}-{time.time_ns()}")
        if username:
            self.client.username_pw_set(username, password)
        self.client.on_connect = self._on_connect
        self.client.on_message = self._on_message
        self.client.connect_async(host, port, keepalive=60)
        self.client.loop_start()

    def _on_connect(self, client, _userdata, _flags, reason, _props):
        if reason.is_failure:
            logger.error("armtwin broker refused the connection: %s", reason)
            return
        client.subscribe([(t, 1) for t in [*self.topics.values(), *self.camera_topics]])

    def _on_message(self, _client, _userdata, msg):
        camera = self.camera_topics.get(msg.topic)
        kind = "camera" if camera else msg.topic.rsplit("/", 1)[-1]
        with self.changed:
            try:
                if camera:
                    self.camera_urls.pop(camera, None)
                    if msg.payload:  # empty: the camera went away
                        self.camera_urls[camera] = mjpeg.mjpeg_url(msg.payload)
                elif kind == "status":
                    text = msg.payload.decode("ascii", "replace")
                    self.present.update(frames.positions(text))
                    for err in frames.errors(text):
                        self.last_error = err
                elif kind == "profile":
                    self.motors = frames.motors_of(msg.payload)
                elif kind == "holder":
                    self.holder = frames.holder_of(msg.payload)
                    if self.holder == self.user:
                        self.held = True
                elif kind == "audit":
                    self._audit(frames.audit_event(msg.payload))
            except ValueError as err:
                self.rejected[f"bad-{kind}"] += 1
                logger.warning("armtwin: %s on %s ignored", err, msg.topic)
            self.changed.notify_all()

    def _audit(self, event: dict) -> None:
        if event["kind"] == "e-stop":
            self.estop = event.get("detail") or f"emergency stop by {event['by'] or 'the plain control topic'}"
            logger.error("armtwin: %s; no action of this session moves the arm any more", self.estop)
        elif event["by"] == self.user and event["kind"] in ("refused-keep-out", "refused-command"):
            self.refused[event["kind"]] += 1
            logger.warning("armtwin refused a command: %s", event.get("detail", event["kind"]))

    def wait(self, what: str, ready, timeout_s: float) -> None:
        """Waits until ready() (called under the lock) is true; TimeoutError naming `what` otherwise."""
        with self.changed:
            if not self.changed.wait_for(ready, timeout_s):
                raise TimeoutError(f"armtwin arm {self.arm!r}: no {what} within {timeout_s} s")

    def take(self, timeout_s: float) -> None:
        """Takes control of the arm as `user` (refused while someone else holds it) and keeps beating."""
        self.wait("profile on the broker (is its controller running?)", lambda: bool(self.motors), timeout_s)
        self.wait(
            "position report",
            lambda: all(m.id in self.present for m in self.motors),
            timeout_s,
        )
        self.client.publish(self.claim, "take", qos=1)
        try:
            self.wait("lease", lambda: self.holder == self.user, timeout_s)
        except TimeoutError as err:
            raise ConnectionError(f"armtwin arm {self.arm!r} is controlled by {self.holder}: ask for control") from err
        self._beating.set()
        threading.Thread(target=self._beat, daemon=True).start()

    def _beat(self) -> None:
        while self._beating.is_set():
            self.client.publish(self.claim, "beat", qos=1)
            time.sleep(BEAT_S)

    def move(self, payload: str) -> None:
        self.client.publish(self.control, payload, qos=1)

    def close(self) -> None:
        if self._beating.is_set():
            self._beating.clear()
            self.client.publish(self.claim, "release", qos=1).wait_for_publish(2)
        self.client.disconnect()
        self.client.loop_stop()
