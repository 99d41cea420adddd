"""Write the committed seed corpus (tests/targets/c/fuzz/corpus/<target>/) from the shared vectors.
Run once when the protocol changes: `python3 tests/targets/c/fuzz/make_seeds.py`."""

from __future__ import annotations

import json
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[3]


def main() -> None:
    doc = json.loads((ROOT / "generated" / "vectors" / "can.json").read_text(encoding="utf-8"))
    names = list(dict.fromkeys(c["message"] for c in doc["cases"]))
    ids = {c["message"]: c["frame_id"] for c in doc["cases"]}
    seeds: dict[str, dict[str, bytes]] = {"unpack": {}, "dispatch": {}, "vin": {}, "monitor": {}}
    for i, name in enumerate(names):
        cases = [c for c in doc["cases"] if c["message"] == name]
        for k, case in enumerate(cases[:3]):
            data = bytes.fromhex(case["data"])
            seeds["unpack"][f"{name}-{k}"] = bytes([i]) + data
            seeds["dispatch"][f"{name}-{k}"] = ids[name].to_bytes(4, "little") + data
        stream = b""
        for k, case in enumerate(cases[:6]):
            stream += bytes([i, 20, 0, 8]) + bytes.fromhex(case["data"])
        seeds["monitor"][name] = stream
    for k, mf in enumerate(doc["multiframe"]):
        frames = [bytes.fromhex(f) for f in mf["frames"]]
        seeds["vin"][f"vin-{k}"] = b"".join(bytes([8]) + f for f in frames)
        seeds["vin"][f"vin-{k}-reversed"] = b"".join(bytes([8]) + f for f in reversed(frames))
    for target, files in seeds.items():
        d = HERE / "corpus" / target
        d.mkdir(parents=True, exist_ok=True)
        for name, data in files.items():
            (d / name).write_bytes(data)


if __name__ == "__main__":
    main()
