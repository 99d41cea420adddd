"""Parquet output read back by DuckDB, pandas and Polars (values checked against cantools); the bulk
decoder mapped over 8 logs on a Dask local cluster gives exactly the single-process tables;
the health report counts what was put into a recording."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pyarrow as pa
import pytest
from canspec.logs import fleet
from repo_paths import CANSPEC_ENV

sys.path.insert(0, str(Path(__file__).resolve().parent))
from logsynth import Frame, drive_frames, frames_from_cases, vector_cases, write


def canspec(*args):
    return subprocess.run([sys.executable, "-m", "canspec", *args], capture_output=True, text=True, env=CANSPEC_ENV, check=False, timeout=300)


@pytest.fixture(scope="module")
def eight_logs(tmp_path_factory, vectors):
    frames = frames_from_cases(vector_cases(vectors), 16000)
    out = tmp_path_factory.mktemp("fleet")
    fmts = ["candump", "blf", "mf4", "asc"]
    return [write(fmts[i % 4], out / f"drive{i}.{['log', 'blf', 'mf4', 'asc'][i % 4]}", frames[i * 2000:(i + 1) * 2000]) for i in range(8)], frames


def test_parquet_read_back_with_duckdb_pandas_polars(eight_logs, tmp_path, db):
    import duckdb
    import pandas as pd
    import polars as pl

    logs, frames = eight_logs
    out = tmp_path / "tables"
    proc = canspec("decode", "--format", "parquet", "--raw", "-o", str(out), *map(str, logs))
    assert proc.returncode == 0, proc.stderr
    cm = db.get_message_by_name("autocar_speed_command")
    mine = [f for f in frames if f.frame_id == cm.frame_id]
    glob = str(out / "autocar_speed_command" / "*" / "*.parquet")
    rows = duckdb.sql(
        f"SELECT source, timestamp, accel_cmd, gear_cmd_label, gear_cmd_raw FROM read_parquet('{glob}', hive_partitioning = true) ORDER BY timestamp"
    ).fetchall()
    assert len(rows) == len(mine)
    for (source, ts, accel, gear, gear_raw), f in zip(rows, mine):
        theirs = cm.decode(f.data)
        assert abs(ts - f.timestamp) < 1e-6 and accel == theirs["accel_cmd"] and gear_raw == cm.decode(f.data, scaling=False, decode_choices=False)["gear_cmd"]
        assert gear == (str(theirs["gear_cmd"]) if not isinstance(theirs["gear_cmd"], (int, float)) else None)
    # partition pruning: one drive only
    one = duckdb.sql(f"SELECT count(*) FROM read_parquet('{glob}', hive_partitioning = true) WHERE source = 'drive3'").fetchall()[0][0]
    assert one == sum(1 for f in frames[6000:8000] if f.frame_id == cm.frame_id)
    frame = pd.read_parquet(out / "autocar_speed_command").sort_values("timestamp")
    assert frame["accel_cmd"].tolist() == [r[2] for r in rows] and str(frame["gear_cmd_raw"].dtype) == "uint8"
    assert isinstance(frame["gear_cmd_label"].dtype, pd.CategoricalDtype)
    polars = pl.read_parquet(str(out / "autocar_speed_command" / "**" / "*.parquet"), hive_partitioning=True).sort("timestamp")
    assert polars["accel_cmd"].to_list() == [r[2] for r in rows] and set(polars["source"].unique()) == {
        f"drive{i}" for i in range(8) if any(f.frame_id == cm.frame_id for f in frames[i * 2000:(i + 1) * 2000])}


def test_dask_local_cluster_gives_the_single_process_tables(eight_logs, can):
    from dask.distributed import Client, LocalCluster

    logs, _ = eight_logs
    single = {}
    for path in logs:
        for name, table in fleet.decode_file(can.messages, str(path)).tables.items():
            single.setdefault(name, []).append(table)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, Client(cluster) as client:
        futures = client.map(fleet.decode_file, [can.messages] * len(logs), list(map(str, logs)), pure=False)
        results = client.gather(futures)
    distributed = {}
    for result in results:
        for name, table in result.tables.items():
            distributed.setdefault(name, []).append(table)
    assert sorted(single) == sorted(distributed) and len(single) == len(can.messages)
    for name, parts in single.items():
        a, b = (pa.concat_tables(t).unify_dictionaries().combine_chunks() for t in (parts, distributed[name]))
        assert a.equals(b), name


def test_health_report_counts_what_was_put_in(can, tmp_path):
    frames = drive_frames(can, 5)
    eps = can.message("autocar_eps_command")
    mine = [i for i, f in enumerate(frames) if f.frame_id == eps.frame_id]
    drop = set(mine[100:110])  # 10 frames missing: one gap of 11 cycles (> the 3-cycle timeout)
    repeat = mine[50]
    bad = mine[60]
    out = []
    for i, f in enumerate(frames):
        if i in drop:
            continue
        if i == repeat:
            out.append(f._replace(data=frames[mine[49]].data))  # the previous frame again: a counter repeat
            continue
        if i == bad:
            f = f._replace(data=f.data[:-1] + bytes([f.data[-1] ^ 1]))
        out.append(f)
    out.append(Frame(out[-1].timestamp + 0.001, 0x18FEEE00, True, bytes(8)))
    log = write("candump", tmp_path / "drive.log", out)
    proc = canspec("decode", "--report", "--format", "json", str(log))
    assert proc.returncode == 0, proc.stderr
    (report,) = json.loads(proc.stdout)["inputs"]
    by = {r["message"]: r for r in report["messages"]}
    r = by["autocar_eps_command"]
    assert r["frames"] == len(mine) - 10 and r["cycle_ms"] == 20 and r["timeout_ms"] == 60
    # the monitor's rules (README): a repeat and a bad checksum are rejected, so the next frame steps
    # the stored counter by 2, within the tolerance of 1: one lost frame each; after the timeout the
    # counter sequence restarts (no jump)
    assert r["counter_repeats"] == 1 and r["lost_frames"] == 2 and r["counter_jumps"] == 0
    assert r["checksum_errors"] == 1 and r["gaps"] == 1 and r["longest_gap_ms"] == pytest.approx(220, abs=0.01)
    assert r["period_ms"] == pytest.approx(20 * (len(mine) - 1) / (len(mine) - 11), abs=1e-3)
    steady = by["vehicle_state_1"]
    assert steady["counter_jumps"] == steady["counter_repeats"] == steady["lost_frames"] == steady["gaps"] == 0 and steady["period_ms"] == pytest.approx(
        50, abs=1e-3
    )
    assert report["unknown_ids"] == {"0x18FEEE00": 1} and report["counts"]["checksum"] == 1
    text = canspec("decode", "--report", str(log)).stdout
    assert "autocar_eps_command" in text and "unknown IDs: 0x18FEEE00 ×1" in text


def test_arrow_frames_round_trip_and_spark_schema(eight_logs, can):
    """What a Spark job does: frame columns through Arrow, decoded per batch, cast to the plain schema."""
    from canspec.logs.bulk import Decoder, decode_arrow
    from canspec.logs.frames import Batch
    from canspec.logs.logread import read_log

    logs, _ = eight_logs
    decoder = Decoder(can.messages)
    for chunk in read_log(str(logs[0])):
        record_batch = chunk.batch.to_arrow()
        assert record_batch.schema.names == ["timestamp", "channel", "frame_id", "extended", "kind", "dlc", "word", "line", "flags"]
        direct = decoder.decode(chunk.batch).tables
        via_arrow = decode_arrow(can.messages, record_batch)
        assert sorted(direct) == sorted(via_arrow) and all(direct[n].equals(via_arrow[n]) for n in direct)
        assert Batch.from_arrow(record_batch).channels == chunk.batch.channels
        for name, table in direct.items():
            plain = table.cast(decoder.layout(name).plain_schema())
            assert not any(pa.types.is_dictionary(f.type) for f in plain.schema)
