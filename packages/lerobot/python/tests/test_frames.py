"""The plugin's pure part: LeRobot's units <-> armtwin's angle frames and records, bad input refused."""
import json
import unittest

from lerobot_robot_armtwin import frames

PAN = frames.Motor("shoulder_pan", 1, -110.0, 110.0)
GRIPPER = frames.Motor("gripper", 6, -10.0, 100.0)


class Frames(unittest.TestCase):
    def test_a_group_of_angle_moves(self):
        self.assertEqual(
            frames.move_group([(PAN, -12.5), (GRIPPER, 45.004)], 0),
            "{#001A-012.50T0000!#006A+045.00T0000!}",
        )

    def test_an_angle_no_frame_can_hold_is_refused(self):
        with self.assertRaisesRegex(ValueError, "shoulder_pan: 1000.0"):
            frames.move_group([(PAN, 1000.0)], 0)
        with self.assertRaises(ValueError):
            frames.move_group([(PAN, float("nan"))], 0)

    def test_the_gripper_is_percent_of_its_limits_and_back(self):
        self.assertAlmostEqual(frames.to_lerobot(GRIPPER, 45.0), 50.0)
        self.assertAlmostEqual(frames.to_degrees(GRIPPER, 0.0), -10.0)
        self.assertAlmostEqual(frames.to_degrees(GRIPPER, 100.0), 100.0)
        self.assertEqual(frames.to_lerobot(PAN, -40.04), -40.04)

    def test_positions_of_a_status_payload(self):
        payload = "$TIM:1795758720122!{#001A+040.04!#006A-002.00!}#001T045V7400!$ERR:controlled by alice!"
        self.assertEqual(frames.positions(payload), {1: 40.04, 6: -2.0})
        self.assertEqual(frames.errors(payload), ["controlled by alice"])

    def test_profile_holder_and_audit_records(self):
        profile = {"name": "so101", "profile": {"servos": [{"id": "001", "name": "shoulder_pan", "min": -110, "max": 110}]}}
        self.assertEqual(frames.motors_of(json.dumps(profile).encode()), [PAN])
        self.assertEqual(frames.holder_of(b'{"user":"lerobot","requests":[]}'), "lerobot")
        self.assertIsNone(frames.holder_of(b'{"user":null,"requests":[]}'))
        self.assertIsNone(frames.holder_of(b""))
        event = frames.audit_event(b'{"at":1,"by":"","kind":"e-stop","detail":"stop"}')
        self.assertEqual(event["kind"], "e-stop")

    def test_bad_records_are_refused_with_what_is_wrong(self):
        for bad in (b"{", b'{"profile":{"servos":[]}}', b'{"profile":{"servos":[{"id":"x"}]}}'):
            with self.assertRaisesRegex(ValueError, "not an armtwin profile announcement"):
                frames.motors_of(bad)
        with self.assertRaisesRegex(ValueError, "not a holder record"):
            frames.holder_of(b'{"user":7}')
        with self.assertRaisesRegex(ValueError, "not an audit event"):
            frames.audit_event(b'{"kind":"e-stop"}')


if __name__ == "__main__":
    unittest.main()
