"""ROS 2 messages <-> the plain JSON objects of the bridge's wire (packages/ros2/src/wire.ts).

Only the fields armtwin uses travel; times are milliseconds. A JSON object that does not fit
raises ValueError with a sentence saying what is wrong (the bridge reports it, kind bad-message).
"""
import math

from builtin_interfaces.msg import Duration, Time
from sensor_msgs.msg import JointState
from std_msgs.msg import String
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

# The message kinds of the wire, each with its ROS 2 type.
TYPES = {
    'joint_state': JointState,
    'joint_trajectory': JointTrajectory,
    'string': String,
}


def _names(obj, field):
    v = obj.get(field)
    if not isinstance(v, list) or not all(isinstance(s, str) for s in v):
        raise ValueError(f'{field} must be a list of strings')
    return v


def _numbers(obj, field, length=None, required=True):
    v = obj.get(field)
    if v is None and not required:
        return []
    if not isinstance(v, list) or not all(
        isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in v
    ):
        raise ValueError(f'{field} must be a list of finite numbers')
    if length is not None and v and len(v) != length:
        raise ValueError(f'{field} has {len(v)} values for {length} joints')
    return [float(x) for x in v]


def _ms(value, field):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (value >= 0):
        raise ValueError(f'{field} must be a number of ms >= 0')
    return value


def _time(ms):
    # Whole milliseconds in integers: ms * 1e6 as a float is past 2**53 for today's epoch times,
    # so a $TIM stamp came back a few hundred ns off (1795763457398 -> ...398.0002).
    whole = int(ms // 1)
    sec, msec = divmod(whole, 1000)
    nsec = msec * 1_000_000 + int(round((ms - whole) * 1e6))
    if nsec >= 1_000_000_000:
        sec, nsec = sec + 1, nsec - 1_000_000_000
    return sec, nsec


def to_ros(kind, obj, now_ms):
    """The ROS 2 message of a wire object of this kind."""
    if not isinstance(obj, dict):
        raise ValueError('msg must be an object')
    if kind == 'string':
        if not isinstance(obj.get('data'), str):
            raise ValueError('data must be a string')
        return String(data=obj['data'])
    if kind == 'joint_state':
        names = _names(obj, 'name')
        m = JointState()
        sec, nsec = _time(_ms(obj.get('stamp_ms', now_ms), 'stamp_ms'))
        m.header.stamp = Time(sec=sec, nanosec=nsec)
        m.name = names
        m.position = _numbers(obj, 'position', len(names))
        m.velocity = _numbers(obj, 'velocity', len(names), required=False)
        m.effort = _numbers(obj, 'effort', len(names), required=False)
        return m
    if kind == 'joint_trajectory':
        names = _names(obj, 'joint_names')
        points = obj.get('points')
        if not isinstance(points, list):
            raise ValueError('points must be a list')
        m = JointTrajectory()
        m.joint_names = names
        for i, p in enumerate(points):
            if not isinstance(p, dict):
                raise ValueError(f'points[{i}] must be an object')
            q = JointTrajectoryPoint()
            q.positions = _numbers(p, 'positions', len(names))
            q.velocities = _numbers(p, 'velocities', len(names), required=False)
            sec, nsec = _time(_ms(p.get('time_from_start_ms'), f'points[{i}].time_from_start_ms'))
            q.time_from_start = Duration(sec=sec, nanosec=nsec)
            m.points.append(q)
        return m
    raise ValueError(f'unknown message type {kind!r}')


def _ms_of(t):
    # Exact for whole milliseconds (a $TIM stamp comes back as it went out).
    msec, rest_ns = divmod(t.nanosec, 1_000_000)
    ms = t.sec * 1000 + msec
    return ms if rest_ns == 0 else ms + rest_ns / 1e6


def from_ros(kind, m):
    """The wire object of a ROS 2 message of this kind."""
    if kind == 'string':
        return {'data': m.data}
    if kind == 'joint_state':
        return {
            'stamp_ms': _ms_of(m.header.stamp),
            'name': list(m.name),
            'position': list(m.position),
            'velocity': list(m.velocity),
            'effort': list(m.effort),
        }
    if kind == 'joint_trajectory':
        return {
            'joint_names': list(m.joint_names),
            'points': [
                {
                    'positions': list(p.positions),
                    'velocities': list(p.velocities),
                    'time_from_start_ms': _ms_of(p.time_from_start),
                }
                for p in m.points
            ],
        }
    raise ValueError(f'unknown message type {kind!r}')
