"""The reference a test engineer writes today: read a candump log, decode every frame with
cantools' `decode_message`, collect the rows per message into pandas and write one Parquet file
per message (same tables as `canspec decode --format parquet`: time stamp, channel, physical
values, value-table labels as strings). cantools does not check checksums: the script flags each
checksum frame itself (`checksum_ok`: the XOR of the covered bytes equals the checksum byte), with
the layouts given as JSON (`[{"frame_id", "byte", "covers"}]`, from the spec).

    python3 bench/reference_parquet.py DBC LOG OUT_DIR [CHECKSUMS_JSON]"""

from __future__ import annotations

import json
import os
import sys
from collections import defaultdict
from functools import reduce
from operator import xor

import cantools
import pandas as pd


def main(dbc: str, log: str, out: str, checksums: str = "[]") -> int:
    db = cantools.database.load_file(dbc, encoding="utf-8")
    checks = {c["frame_id"]: (c["byte"], c["covers"]) for c in json.loads(checksums)}
    rows: dict[str, list[dict[str, object]]] = defaultdict(list)
    with open(log, encoding="ascii") as lines:
        for line in lines:
            stamp, channel, frame = line.split()[:3]
            frame_id, data = frame.split("#")
            msg = db.get_message_by_frame_id(int(frame_id, 16))
            payload = bytes.fromhex(data)
            values = db.decode_message(msg.frame_id, payload)
            row: dict[str, object] = {"timestamp": float(stamp[1:-1]), "channel": channel}
            for name, value in values.items():
                if isinstance(value, (int, float)):
                    row[name] = float(value)
                else:
                    row[name] = float(msg.get_signal_by_name(name).conversion.choice_to_number(value))
                    row[f"{name}_label"] = str(value)
            if msg.frame_id in checks:
                byte, covers = checks[msg.frame_id]
                row["checksum_ok"] = reduce(xor, (payload[i] for i in covers)) == payload[byte]
            rows[msg.name].append(row)
    for name, records in rows.items():
        os.makedirs(os.path.join(out, name), exist_ok=True)
        frame = pd.DataFrame.from_records(records)
        for col in frame.columns:
            if col.endswith("_label") or col == "channel":
                frame[col] = frame[col].astype("category")
        frame.to_parquet(os.path.join(out, name, "part-0.parquet"), compression="zstd")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))
