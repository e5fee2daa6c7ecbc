"""Drives an emulated Feetech STS bus with Feetech's own Python SDK (feetech-servo-sdk,
module scservo_sdk) and prints what it saw as one JSON object. Used by
tests/integration/servo-bus-sdk.test.ts.

    python feetech_check.py PORT BAUD

Servos expected: STS3215 ids 1 and 2; id 3 absent.
"""
import json
import sys
import time
from importlib.metadata import version

from sdk_check import make_txrx, ping_checks, wait_until

import scservo_sdk.port_handler as scs_port
from scservo_sdk import (COMM_SUCCESS, SCS_HIBYTE, SCS_HIWORD, SCS_LOBYTE, SCS_LOWORD, SCS_TOHOST, SCS_TOSCS,
                         GroupSyncRead, GroupSyncWrite, PacketHandler, PortHandler)

# As in dynamixel_check.py: answers over a pty on a busy machine may take longer than a USB adapter's.
scs_port.LATENCY_TIMER = 50

ADDR_MIN_LIMIT, ADDR_MAX_LIMIT = 9, 11
ADDR_TORQUE, ADDR_GOAL, ADDR_GOAL_SPEED = 40, 42, 46
ADDR_PRESENT, ADDR_VOLTAGE, ADDR_TEMPERATURE, ADDR_MOVING = 56, 62, 63, 66

port = PortHandler(sys.argv[1])
ph = PacketHandler(0)  # protocol_end 0: STS/SMS, little-endian words
out = {"sdk": "feetech-servo-sdk " + version("feetech-servo-sdk"), "retries": 0}
if not port.openPort() or not port.setBaudRate(int(sys.argv[2])):
    sys.exit("cannot open " + sys.argv[1])


def settle():
    """After a lost answer: let a late one land, then drop it (this SDK's clearPort only flushes output)."""
    time.sleep(0.05)
    port.ser.reset_input_buffer()


txrx = make_txrx(port, ph, out, COMM_SUCCESS, settle)


# PING (this SDK then READs the model number at address 3).
ping_checks(txrx, ph, port, out)
settle()

# Present position, temperature, voltage (0.1 V).
out["present"] = {}
for i in (1, 2):
    pos, _, _ = txrx(ph.read2ByteTxRx, i, ADDR_PRESENT)
    temp, _, _ = txrx(ph.read1ByteTxRx, i, ADDR_TEMPERATURE)
    volt, _, error = txrx(ph.read1ByteTxRx, i, ADDR_VOLTAGE)
    out["present"][i] = {"position": SCS_TOHOST(pos, 15), "temperature": temp, "voltage": volt / 10, "error": error}

# Torque on, and read back.
for i in (1, 2):
    txrx(ph.write1ByteTxRx, i, ADDR_TORQUE, 1)
out["torque_on"] = [txrx(ph.read1ByteTxRx, i, ADDR_TORQUE)[0] for i in (1, 2)]

# A goal at a goal speed (steps/s), watched until reached.
txrx(ph.write2ByteTxRx, 1, ADDR_GOAL_SPEED, 400)
txrx(ph.write2ByteTxRx, 1, ADDR_GOAL, 3072)
seen = []


def reached_single():
    # Moving first: a servo already stopped when asked is where the next read finds it.
    moving = txrx(ph.read1ByteTxRx, 1, ADDR_MOVING)[0]
    pos = SCS_TOHOST(txrx(ph.read2ByteTxRx, 1, ADDR_PRESENT)[0], 15)
    seen.append(pos)
    return moving == 0 and abs(pos - 3072) <= 10


out["goal"] = wait_until(reached_single)
out["goal"].update({"final": seen[-1], "in_between": sum(1 for p in seen if 2048 < p < 3072)})

# GroupSyncWrite goals, GroupSyncRead position and speed until both are there.
goals = {1: 1024, 2: 2500}
sync_write = GroupSyncWrite(port, ph, ADDR_GOAL, 2)
for i, g in goals.items():
    sync_write.addParam(i, [SCS_LOBYTE(g), SCS_HIBYTE(g)])
out["sync_write"] = ph.getTxRxResult(sync_write.txPacket())
sync_read = GroupSyncRead(port, ph, ADDR_PRESENT, 4)
for i in goals:
    sync_read.addParam(i)
last = {}
speeds = set()


def reached_sync():
    if sync_read.txRxPacket() != COMM_SUCCESS:
        out["retries"] += 1
        settle()
        return False
    for i in goals:
        word = sync_read.getData(i, ADDR_PRESENT, 4)
        last[i] = SCS_TOHOST(SCS_LOWORD(word), 15)
        speeds.add(SCS_TOHOST(SCS_HIWORD(word), 15))
    return all(last[i] == g for i, g in goals.items())


out["sync"] = wait_until(reached_sync)
out["sync"].update({"final": last, "negative_speed_seen": any(s < 0 for s in speeds)})

# Multi-turn: angle limits 0 and 0, a negative goal in the sign bit encoding.
txrx(ph.write2ByteTxRx, 2, ADDR_MIN_LIMIT, 0)
txrx(ph.write2ByteTxRx, 2, ADDR_MAX_LIMIT, 0)
txrx(ph.write2ByteTxRx, 2, ADDR_GOAL, SCS_TOSCS(-500, 15))
out["negative"] = wait_until(lambda: SCS_TOHOST(txrx(ph.read2ByteTxRx, 2, ADDR_PRESENT)[0], 15) == -500)

# Torque off.
for i in (1, 2):
    txrx(ph.write1ByteTxRx, i, ADDR_TORQUE, 0)
out["torque_off"] = [txrx(ph.read1ByteTxRx, i, ADDR_TORQUE)[0] for i in (1, 2)]

port.closePort()
print(json.dumps(out))
