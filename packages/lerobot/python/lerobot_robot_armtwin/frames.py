"""The contract's frames and armtwin's records as LeRobot's units, free of I/O (PROTOCOL.md §1,
§8; docs/protocol.md § Control). Positions are servo angles in degrees (§8 angle frames); a
servo named "gripper" is 0-100 % of its limits, as LeRobot's SO follower counts it."""

import json
import re
from dataclasses import dataclass

ANGLE_REPORT = re.compile(r"#(\d{3})A([+-]\d{3}\.\d{2})!")
ERROR = re.compile(r"\$ERR:([^!]*)!")
GRIPPER = "gripper"
MAX_ANGLE = 999.99


@dataclass(frozen=True)
class Motor:
    """One servo of the arm's profile: LeRobot's motor name, armtwin's id and limits (degrees)."""

    name: str
    id: int
    min: float
    max: float


def motors_of(announcement: bytes) -> list[Motor]:
    """The motors of a retained arm/{id}/profile announcement ({name, title, profile}); ValueError if it is not one."""
    try:
        servos = json.loads(announcement)["profile"]["servos"]
        motors = [Motor(str(s["name"]), int(s["id"]), float(s["min"]), float(s["max"])) for s in servos]
    except (ValueError, KeyError, TypeError) as err:
        raise ValueError(f"not an armtwin profile announcement: {err}") from err
    if not motors:
        raise ValueError("not an armtwin profile announcement: no servos")
    return motors


def to_lerobot(motor: Motor, degrees: float) -> float:
    """armtwin's servo angle -> LeRobot's value (the gripper in % of its range)."""
    if motor.name == GRIPPER:
        return (degrees - motor.min) / (motor.max - motor.min) * 100.0
    return degrees


def to_degrees(motor: Motor, value: float) -> float:
    """LeRobot's value -> armtwin's servo angle."""
    if motor.name == GRIPPER:
        return motor.min + value / 100.0 * (motor.max - motor.min)
    return value


def move_group(goals: list[tuple[Motor, float]], ms: int) -> str:
    """One group of §8 angle moves (all start together, or none does): `{#001A+012.50T0000!…}`."""
    frames = []
    for motor, deg in goals:
        if not abs(deg) <= MAX_ANGLE:
            raise ValueError(f"{motor.name}: {deg}° cannot be sent (an angle frame holds ±{MAX_ANGLE})")
        frames.append(f"#{motor.id:03d}A{'+' if deg >= 0 else '-'}{abs(deg):06.2f}T{ms:04d}!")
    return "{" + "".join(frames) + "}"


def positions(payload: str) -> dict[int, float]:
    """The angle reports (`#IIIA±ddd.dd!`) in a status payload, by servo id."""
    return {int(i): float(a) for i, a in ANGLE_REPORT.findall(payload)}


def errors(payload: str) -> list[str]:
    """The `$ERR:text!` frames of a status payload."""
    return ERROR.findall(payload)


def holder_of(record: bytes) -> str | None:
    """The user of an arm/{id}/holder record (None: nobody); ValueError if it is not one."""
    if not record:
        return None
    try:
        user = json.loads(record)["user"]
    except (ValueError, KeyError, TypeError) as err:
        raise ValueError(f"not a holder record: {err}") from err
    if user is not None and not isinstance(user, str):
        raise ValueError("not a holder record: user is neither a name nor null")
    return user


def audit_event(payload: bytes) -> dict:
    """An arm/{id}/audit event {at, by, kind, detail}; ValueError if it is not one."""
    try:
        event = json.loads(payload)
        if not (isinstance(event["kind"], str) and isinstance(event["by"], str)):
            raise TypeError("kind and by are not text")
    except (ValueError, KeyError, TypeError) as err:
        raise ValueError(f"not an audit event: {err}") from err
    return event
