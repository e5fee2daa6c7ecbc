"""One armtwin camera read as LeRobot observes it: its MJPEG stream (armtwin's camera server, the
URL its announcement gives) read on a thread, the newest JPEG kept, decoded to RGB only when an
observation asks for it (and only once per frame). A stream that breaks is opened again after
half a second; what went wrong is counted by kind (`counters`)."""

import base64
import logging
import threading
import time
import urllib.request
from collections import Counter

import cv2
import numpy as np

from .mjpeg import MultipartReader, boundary_of

logger = logging.getLogger(__name__)
RETRY_S = 0.5


class CameraStream:
    def __init__(
        self, name: str, url: str, width: int, height: int, username: str | None = None, password: str | None = None
    ):
        self.name, self.url, self.shape = name, url, (height, width, 3)
        self.auth = (
            "Basic " + base64.b64encode(f"{username}:{password or ''}".encode()).decode() if username else None
        )
        self.counters = Counter()
        self.last_error = ""
        self.lock = threading.Lock()
        self.arrived = threading.Condition(self.lock)
        self.jpeg: bytes | None = None
        self.sequence = -1  # of the newest JPEG, counted here
        self.received = 0.0  # time.monotonic() of the newest JPEG
        self.decoded: tuple[int, np.ndarray] | None = None
        self.running = threading.Event()
        self.response = None
        self.thread: threading.Thread | None = None

    def start(self, timeout_s: float) -> None:
        """Reads the stream; returns once a first picture came (TimeoutError otherwise)."""
        self.running.set()
        self.thread = threading.Thread(target=self._run, name=f"armtwin-camera-{self.name}", daemon=True)
        self.thread.start()
        with self.arrived:
            if not self.arrived.wait_for(lambda: self.jpeg is not None, timeout_s):
                self.stop()
                raise TimeoutError(
                    f"armtwin camera {self.name!r}: no picture from {self.url} within {timeout_s} s"
                    + (f" ({self.last_error})" if self.last_error else "")
                )

    def read_latest(self, max_age_s: float) -> np.ndarray:
        """The newest picture, RGB, `(height, width, 3)` uint8; an error when it is older than
        `max_age_s` (the stream stalled) or not the configured size."""
        with self.lock:
            jpeg, seq, age = self.jpeg, self.sequence, time.monotonic() - self.received
            cached = self.decoded
        if jpeg is None or age > max_age_s:
            raise TimeoutError(
                f"armtwin camera {self.name!r}: no picture for {age:.1f} s"
                + (f" ({self.last_error})" if self.last_error else "")
            )
        if cached is not None and cached[0] == seq:
            return cached[1]
        bgr = cv2.imdecode(np.frombuffer(jpeg, np.uint8), cv2.IMREAD_COLOR)
        if bgr is None:
            self.counters["bad-jpeg"] += 1
            raise ValueError(f"armtwin camera {self.name!r}: a picture that is not a JPEG")
        if bgr.shape != self.shape:
            self.counters["wrong-size"] += 1
            raise ValueError(
                f"armtwin camera {self.name!r} sends {bgr.shape[1]}x{bgr.shape[0]}, "
                f"configured {self.shape[1]}x{self.shape[0]} (its width and height)"
            )
        rgb = cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)
        with self.lock:
            self.decoded = (seq, rgb)
        return rgb

    def stop(self) -> None:
        self.running.clear()
        r = self.response
        if r is not None:
            try:
                r.close()
            except OSError:
                pass
        if self.thread is not None and self.thread is not threading.current_thread():
            self.thread.join(2)

    def _run(self) -> None:
        while self.running.is_set():
            try:
                self._read()
            except Exception as err:  # noqa: BLE001 - any failure of the stream: counted, then again
                if not self.running.is_set():
                    return
                kind = "bad-stream" if isinstance(err, ValueError) else "stream-lost"
                self.counters[kind] += 1
                self.last_error = f"{kind}: {err}"
                if self.counters[kind] == 1:
                    logger.warning("armtwin camera %s: %s; opening it again", self.name, self.last_error)
                time.sleep(RETRY_S)

    def _read(self) -> None:
        req = urllib.request.Request(self.url, headers={"Authorization": self.auth} if self.auth else {})
        with urllib.request.urlopen(req, timeout=10) as r:
            self.response = r
            reader = MultipartReader(boundary_of(r.headers.get("Content-Type", "")))
            while self.running.is_set():
                chunk = r.read1(65536)
                if not chunk:
                    raise ConnectionError("the stream ended")
                for headers, body in reader.feed(chunk):
                    self._take(headers, body)

    def _take(self, _headers: dict[str, str], body: bytes) -> None:
        self.counters["frames"] += 1
        with self.arrived:
            self.sequence += 1  # ours, not the server's X-Sequence (which starts again with ffmpeg)
            self.jpeg = body
            self.received = time.monotonic()
            self.arrived.notify_all()
