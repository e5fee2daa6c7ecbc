"""Drives an emulated Dynamixel bus with ROBOTIS's own Python SDK (dynamixel-sdk, Protocol 2.0)
and prints what it saw as one JSON object. Used by tests/integration/servo-bus-sdk.test.ts.

    python dynamixel_check.py PORT BAUD

Servos expected: id 1 and id 2, position mode; id 3 absent.
"""
import json
import sys
import time
from importlib.metadata import version

from sdk_check import make_txrx, ping_checks, wait_until

import dynamixel_sdk.port_handler as dxl_port
from dynamixel_sdk import (COMM_SUCCESS, DXL_HIBYTE, DXL_HIWORD, DXL_LOBYTE, DXL_LOWORD, GroupSyncRead,
                           GroupSyncWrite, PacketHandler, PortHandler)

# The SDK waits 2 x LATENCY_TIMER + 2 ms (+ transfer time) for an answer; 16 ms suits a USB
# adapter, not a pty on a busy test machine. The SDK keeps this in a module constant for users to tune.
dxl_port.LATENCY_TIMER = 50

ADDR_TORQUE, ADDR_MOVING, ADDR_PROFILE_VELOCITY, ADDR_GOAL, ADDR_PRESENT = 64, 122, 112, 116, 132
ADDR_VOLTAGE, ADDR_TEMPERATURE = 144, 146

port = PortHandler(sys.argv[1])
ph = PacketHandler(2.0)
out = {"sdk": "dynamixel-sdk " + version("dynamixel-sdk"), "retries": 0}
if not port.openPort() or not port.setBaudRate(int(sys.argv[2])):
    sys.exit("cannot open " + sys.argv[1])


def settle():
    """After a lost answer: let a late one land, then drop it."""
    time.sleep(0.05)
    port.clearPort()


txrx = make_txrx(port, ph, out, COMM_SUCCESS, settle)


def as_signed(v):
    return v - (1 << 32) if v >= 1 << 31 else v


# PING: model number and firmware come with the answer.
ping_checks(txrx, ph, port, out)
found, comm = ph.broadcastPing(port)
out["broadcast_ping"] = {str(k): v[0] for k, v in sorted(found.items())}

# Present position, temperature, voltage.
out["present"] = {}
for i in (1, 2):
    pos, _, _ = txrx(ph.read4ByteTxRx, i, ADDR_PRESENT)
    temp, _, _ = txrx(ph.read1ByteTxRx, i, ADDR_TEMPERATURE)
    volt, _, _ = txrx(ph.read2ByteTxRx, i, ADDR_VOLTAGE)
    out["present"][i] = {"position": as_signed(pos), "temperature": temp, "voltage": volt / 10}

# Torque on, and read back.
for i in (1, 2):
    txrx(ph.write1ByteTxRx, i, ADDR_TORQUE, 1)
out["torque_on"] = [txrx(ph.read1ByteTxRx, i, ADDR_TORQUE)[0] for i in (1, 2)]

# A goal at a profile velocity, watched until reached.
txrx(ph.write4ByteTxRx, 1, ADDR_PROFILE_VELOCITY, 50)
txrx(ph.write4ByteTxRx, 1, ADDR_GOAL, 3072)
seen = []


def reached_single():
    # Moving first: a servo already stopped when asked is where the next read finds it.
    moving = txrx(ph.read1ByteTxRx, 1, ADDR_MOVING)[0]
    pos = as_signed(txrx(ph.read4ByteTxRx, 1, ADDR_PRESENT)[0])
    seen.append(pos)
    return moving == 0 and abs(pos - 3072) <= 10


out["goal"] = wait_until(reached_single)
out["goal"].update({"final": seen[-1], "in_between": sum(1 for p in seen if 2048 < p < 3072)})

# GroupSyncWrite goals, GroupSyncRead present positions until both are there.
goals = {1: 1024, 2: 2500}
sync_write = GroupSyncWrite(port, ph, ADDR_GOAL, 4)
for i, g in goals.items():
    sync_write.addParam(i, [DXL_LOBYTE(DXL_LOWORD(g)), DXL_HIBYTE(DXL_LOWORD(g)), DXL_LOBYTE(DXL_HIWORD(g)), DXL_HIBYTE(DXL_HIWORD(g))])
out["sync_write"] = ph.getTxRxResult(sync_write.txPacket())
sync_read = GroupSyncRead(port, ph, ADDR_PRESENT, 4)
for i in goals:
    sync_read.addParam(i)
last = {}


def reached_sync():
    if sync_read.txRxPacket() != COMM_SUCCESS:
        out["retries"] += 1
        time.sleep(0.05)
        port.clearPort()
        return False
    for i in goals:
        last[i] = as_signed(sync_read.getData(i, ADDR_PRESENT, 4))
    return all(last[i] == g for i, g in goals.items())


out["sync"] = wait_until(reached_sync)
out["sync"]["final"] = last

# The status error byte: a goal past Max Position Limit is refused with a Data Limit Error.
comm, error = txrx(ph.write4ByteTxRx, 1, ADDR_GOAL, 5000)
out["limit_error"] = {"error": error, "text": ph.getRxPacketError(error)}

# Torque off.
for i in (1, 2):
    txrx(ph.write1ByteTxRx, i, ADDR_TORQUE, 0)
out["torque_off"] = [txrx(ph.read1ByteTxRx, i, ADDR_TORQUE)[0] for i in (1, 2)]

port.closePort()
print(json.dumps(out))
