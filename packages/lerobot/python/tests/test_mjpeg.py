"""The plugin's pure MJPEG part: an armtwin camera announcement's stream URL, and a multipart
stream cut into its parts whatever the chunks, bad input refused."""
import json
import unittest

from lerobot_robot_armtwin import mjpeg

PART = b"--armtwin-frame\r\nContent-Type: image/jpeg\r\nContent-Length: %d\r\nX-Sequence: %d\r\n\r\n%s\r\n"


def stream(*bodies: bytes) -> bytes:
    return b"".join(PART % (len(b), i, b) for i, b in enumerate(bodies))


class Announcement(unittest.TestCase):
    def test_the_main_mjpeg_stream_or_an_mjpeg_alternate(self):
        main = {"url": "http://127.0.0.1:8090/camera/front.mjpeg", "kind": "mjpeg", "label": "Front"}
        self.assertEqual(mjpeg.mjpeg_url(json.dumps(main).encode()), main["url"])
        h264 = {
            "url": "ws://127.0.0.1:8090/camera/front.h264",
            "kind": "h264-ws",
            "label": "Front",
            "alternates": [{"url": "http://h:1/camera/front.mjpeg", "kind": "mjpeg"}],
        }
        self.assertEqual(mjpeg.mjpeg_url(json.dumps(h264).encode()), "http://h:1/camera/front.mjpeg")

    def test_no_mjpeg_stream_or_not_json_is_refused(self):
        with self.assertRaisesRegex(ValueError, "no MJPEG stream"):
            mjpeg.mjpeg_url(b'{"url": "ws://h/x.h264", "kind": "h264-ws"}')
        with self.assertRaisesRegex(ValueError, "not JSON"):
            mjpeg.mjpeg_url(b"{")
        with self.assertRaisesRegex(ValueError, "not an object"):
            mjpeg.mjpeg_url(b"[]")


class Multipart(unittest.TestCase):
    def test_the_boundary_of_the_content_type(self):
        self.assertEqual(mjpeg.boundary_of("multipart/x-mixed-replace; boundary=armtwin-frame"), b"armtwin-frame")
        self.assertEqual(mjpeg.boundary_of('multipart/x-mixed-replace;boundary="--b"'), b"b")
        with self.assertRaisesRegex(ValueError, "not an MJPEG stream"):
            mjpeg.boundary_of("text/html")

    def test_parts_by_content_length_in_any_chunks(self):
        data = stream(b"\xff\xd8one\xff\xd9", b"\xff\xd8two--armtwin-frame\xff\xd9")
        for size in (1, 7, len(data)):
            r = mjpeg.MultipartReader(b"armtwin-frame")
            parts = [p for i in range(0, len(data), size) for p in r.feed(data[i : i + size])]
            self.assertEqual([b for _, b in parts], [b"\xff\xd8one\xff\xd9", b"\xff\xd8two--armtwin-frame\xff\xd9"])
            self.assertEqual(parts[1][0]["x-sequence"], "1")

    def test_parts_without_content_length_end_at_the_next_boundary(self):
        r = mjpeg.MultipartReader(b"b")
        parts = r.feed(b"--b\r\nContent-Type: image/jpeg\r\n\r\nAAA\r\n--b\r\n\r\nBB\r\n--b\r\n")
        self.assertEqual([b for _, b in parts], [b"AAA", b"BB"])

    def test_a_bad_length_or_an_endless_part_is_refused(self):
        with self.assertRaisesRegex(ValueError, "bad Content-Length"):
            mjpeg.MultipartReader(b"b").feed(b"--b\r\nContent-Length: -1\r\n\r\n")
        with self.assertRaisesRegex(ValueError, "size limit"):
            mjpeg.MultipartReader(b"b", max_part=10).feed(b"--b\r\n\r\n" + b"x" * 20)


if __name__ == "__main__":
    unittest.main()
