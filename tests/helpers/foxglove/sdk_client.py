"""A foxglove.sdk.v1 client for the tests, on the `websockets` library (foxglove-sdk 0.30.3 has
no client: scripts/pyenv-foxglove.sh). Input, JSON on stdin:
  {"url", "user", "password", "topics": {topic: count}, "timeout": s}
It connects offering only foxglove.sdk.v1 (with HTTP Basic when a user is given), reads
serverInfo and the advertised channels, subscribes to `topics`, and prints one JSON object:
  {"protocol", "serverInfo", "channels": [topic…], "messages": {topic: [{"ns", "body"}…]}}
with the first `count` messages of each topic."""
import asyncio
import base64
import json
import struct
import sys

import websockets


async def main(o):
    headers = {}
    if o.get("user"):
        token = base64.b64encode(f"{o['user']}:{o['password']}".encode()).decode()
        headers["Authorization"] = f"Basic {token}"
    async with websockets.connect(
        o["url"], subprotocols=["foxglove.sdk.v1"], additional_headers=headers, max_size=None
    ) as ws:
        out = {"protocol": ws.subprotocol, "serverInfo": None, "channels": [], "messages": {}}
        by_topic = {}
        subs = {}
        want = o["topics"]

        def done():
            return all(len(out["messages"].get(t, [])) >= n for t, n in want.items())

        async def read():
            while not done():
                raw = await ws.recv()
                if isinstance(raw, str):
                    m = json.loads(raw)
                    if m["op"] == "serverInfo":
                        out["serverInfo"] = m
                    elif m["op"] == "advertise":
                        new = []
                        for c in m["channels"]:
                            by_topic[c["topic"]] = c
                            out["channels"].append(c["topic"])
                            if c["topic"] in want and c["topic"] not in subs.values():
                                sub = len(subs) + 1
                                subs[sub] = c["topic"]
                                new.append({"id": sub, "channelId": c["id"]})
                        if new:
                            await ws.send(json.dumps({"op": "subscribe", "subscriptions": new}))
                elif raw[0] == 1:  # Message Data: opcode, u32 subscription, u64 ns, payload
                    sub, ns = struct.unpack_from("<IQ", raw, 1)
                    topic = subs.get(sub)
                    if topic is not None:
                        out["messages"].setdefault(topic, []).append(
                            {"ns": str(ns), "body": json.loads(raw[13:].decode())}
                        )

        await asyncio.wait_for(read(), o.get("timeout", 20))
        for t in out["messages"]:
            out["messages"][t] = out["messages"][t][: want[t]]
        print(json.dumps(out))


asyncio.run(main(json.load(sys.stdin)))
