"""Drive Debian's python3-tf2 BufferCore (the tf2 C++ core) with a script of operations.

Run with Debian's /usr/bin/python3 (where tf2_py, genpy and geometry_msgs live), not the
project's interpreter: reads a JSON list of scripts ``{"cache_ns": N, "ops": [...]}`` on stdin
and writes, per script, the list of results of its lookups.
"""

import json
import sys

import genpy
import tf2_py as tf2
from geometry_msgs.msg import TransformStamped


def stamp(ns):
    return genpy.Time(ns // 1_000_000_000, ns % 1_000_000_000)


def classify(exc):
    text = str(exc)
    if isinstance(exc, tf2.LookupException):
        return "lookup"
    if isinstance(exc, tf2.ConnectivityException):
        return "connectivity"
    if isinstance(exc, tf2.ExtrapolationException):
        if "into the future" in text:
            return "future"
        if "into the past" in text:
            return "past"
        return "nodata"
    if isinstance(exc, tf2.InvalidArgumentException):
        return "invalid"
    return "other"


def run(script):
    buf = tf2.BufferCore(genpy.Duration(0, 0) + genpy.Duration.from_sec(script["cache_ns"] / 1e9))
    out = []
    for op in script["ops"]:
        if op["op"] == "set":
            t = TransformStamped()
            t.header.frame_id = op["parent"]
            t.child_frame_id = op["child"]
            t.header.stamp = stamp(op["stamp"])
            t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = op["t"]
            q = t.transform.rotation
            q.x, q.y, q.z, q.w = op["q"]
            if op["static"]:
                buf.set_transform_static(t, "oracle")
            else:
                buf.set_transform(t, "oracle")
        else:
            try:
                r = buf.lookup_transform_core(op["target"], op["source"], stamp(op["time"]))
                tr, ro = r.transform.translation, r.transform.rotation
                out.append(
                    {
                        "kind": "ok",
                        "t": [tr.x, tr.y, tr.z],
                        "q": [ro.x, ro.y, ro.z, ro.w],
                        "stamp": r.header.stamp.to_nsec(),
                    }
                )
            except Exception as exc:  # every tf2 exception is a result here
                out.append({"kind": classify(exc), "message": str(exc)})
    return out


def main():
    json.dump([run(script) for script in json.load(sys.stdin)], sys.stdout)


if __name__ == "__main__":
    main()
