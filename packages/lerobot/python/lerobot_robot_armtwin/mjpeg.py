"""The plugin's pure MJPEG side: the camera's stream URL out of its armtwin announcement
(`arm/{arm}/camera/{name}`, retained JSON `{url, kind, label, alternates?}`: PROTOCOL §7), and
the parts of a `multipart/x-mixed-replace` stream (armtwin's camera server, IP cameras,
mjpg-streamer), cut from the bytes as they come. Bad input is a `ValueError`."""

import json


def mjpeg_url(payload: bytes) -> str:
    """The MJPEG stream of a camera announcement: its main stream or an `mjpeg` alternate."""
    try:
        a = json.loads(payload)
    except (ValueError, UnicodeDecodeError) as err:
        raise ValueError(f"camera announcement: not JSON ({err})") from None
    if not isinstance(a, dict):
        raise ValueError("camera announcement: not an object")
    streams = [a, *(s for s in a.get("alternates") or [] if isinstance(s, dict))]
    for s in streams:
        url = s.get("url")
        if s.get("kind") == "mjpeg" and isinstance(url, str) and url.startswith(("http://", "https://")):
            return url
    raise ValueError(f"camera announcement: no MJPEG stream (kinds: {[s.get('kind') for s in streams]})")


def boundary_of(content_type: str) -> bytes:
    """The boundary of a `multipart/x-mixed-replace; boundary=…` content type."""
    kind, _, params = content_type.partition(";")
    if kind.strip().lower() != "multipart/x-mixed-replace":
        raise ValueError(f"not an MJPEG stream: {content_type!r}")
    for p in params.split(";"):
        k, _, v = p.strip().partition("=")
        if k.lower() == "boundary" and v:
            return v.strip('"').removeprefix("--").encode("latin-1")
    raise ValueError(f"no boundary in {content_type!r}")


class MultipartReader:
    """Feeds a multipart stream's bytes in any chunks; `feed` returns the parts completed, each
    `(headers, body)` (header names lower-case). A part with `Content-Length` ends there; one
    without ends at the next boundary. Holds at most `max_part` bytes for one part."""

    def __init__(self, boundary: bytes, max_part: int = 16 << 20):
        self.delimiter = b"--" + boundary
        self.max_part = max_part
        self.buf = b""
        self.headers: dict[str, str] | None = None

    def feed(self, chunk: bytes) -> list[tuple[dict[str, str], bytes]]:
        self.buf += chunk
        parts = []
        while True:
            if self.headers is None:
                start = self.buf.find(self.delimiter)
                end = self.buf.find(b"\r\n\r\n", start) if start >= 0 else -1
                if end < 0:
                    if len(self.buf) > self.max_part:
                        raise ValueError("no part header within the size limit")
                    return parts
                lines = self.buf[start + len(self.delimiter) : end].decode("latin-1").split("\r\n")
                self.headers = {}
                for line in lines:
                    k, sep, v = line.partition(":")
                    if sep:
                        self.headers[k.strip().lower()] = v.strip()
                self.buf = self.buf[end + 4 :]
            length = self.headers.get("content-length")
            if length is not None:
                if not length.isdigit() or int(length) > self.max_part:
                    raise ValueError(f"bad Content-Length {length!r}")
                n = int(length)
                if len(self.buf) < n:
                    return parts
                body, self.buf = self.buf[:n], self.buf[n:]
            else:
                n = self.buf.find(b"\r\n" + self.delimiter)
                if n < 0:
                    if len(self.buf) > self.max_part:
                        raise ValueError("a part over the size limit")
                    return parts
                body, self.buf = self.buf[:n], self.buf[n + 2 :]
            parts.append((self.headers, body))
            self.headers = None
