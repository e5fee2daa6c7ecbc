"""What the two vendor-SDK checks share: asking again after a lost answer, waiting for a goal,
and the pings. Imported by dynamixel_check.py and feetech_check.py (same folder)."""
import time


def make_txrx(port, ph, out, success, settle):
    """One SDK call; a lost answer is asked again (a host does), at most 3 times, and counted in
    out["retries"]. `settle` runs after each lost answer."""

    def txrx(fn, *args):
        for _ in range(4):
            r = fn(port, *args)
            comm = r[1] if len(r) == 3 else r[0]
            if comm == success:
                return r
            out["retries"] += 1
            settle()
        raise RuntimeError("%s%r: %s" % (fn.__name__, args, ph.getTxRxResult(comm)))

    return txrx


def wait_until(check, timeout=10.0):
    start = time.monotonic()
    polls = 0
    while time.monotonic() - start < timeout:
        polls += 1
        if check():
            return {"seconds": round(time.monotonic() - start, 3), "polls": polls}
        time.sleep(0.02)
    raise RuntimeError("not reached in %.0f s" % timeout)


def ping_checks(txrx, ph, port, out):
    """Servos 1 and 2 answer with their model number; servo 3 is absent."""
    out["ping"] = {}
    for i in (1, 2):
        model, _, error = txrx(ph.ping, i)
        out["ping"][i] = {"model": model, "error": error}
    _, comm, _ = ph.ping(port, 3)
    out["ping_absent"] = ph.getTxRxResult(comm)
