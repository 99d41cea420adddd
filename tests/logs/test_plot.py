"""`canspec plot`: rendered to files on the Agg backend; the image's size is checked, and the data
points on the axes are the values cantools decodes from the frames written into the log."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.image
import matplotlib.pyplot as plt
import numpy as np
import pytest
from canspec import cli
from repo_paths import CANSPEC_ENV

sys.path.insert(0, str(Path(__file__).resolve().parent))
from logsynth import drive_frames, write


@pytest.fixture(scope="module")
def drive(tmp_path_factory, can):
    frames = drive_frames(can, 6)
    return write("blf", tmp_path_factory.mktemp("plot") / "drive.blf", frames), frames


def test_png_svg_pdf_files(drive, tmp_path):
    log, _ = drive
    for ext, magic in (("png", b"\x89PNG"), ("svg", b"<?xml"), ("pdf", b"%PDF")):
        out = tmp_path / f"p.{ext}"
        proc = subprocess.run([sys.executable, "-m", "canspec", "plot", str(log), "accel_*", "steering_angle_cmd", "-o", str(out), "--dpi", "50"],
                              capture_output=True, text=True, env=CANSPEC_ENV, check=False, timeout=120)
        assert proc.returncode == 0, proc.stderr
        assert out.read_bytes().startswith(magic)
    image = matplotlib.image.imread(str(tmp_path / "p.png"))
    assert image.shape[:2] == (300, 500)  # two units (m/s², deg): 10 × (2 × 2.2 + 1.6) inches at 50 dpi
    assert image[..., :3].std() > 0.05  # not blank


def test_plotted_points_are_the_decoded_values(drive, db, tmp_path):
    log, frames = drive
    plt.close("all")
    assert cli.main(["plot", str(log), "autocar_speed_command.accel_cmd", "autocar_speed_command.gear_cmd", "--stack", "--start", "1", "--stop", "5",
                     "-o", str(tmp_path / "s.png")]) == 0
    fig = plt.gcf()
    cm = db.get_message_by_name("autocar_speed_command")
    mine = [f for f in frames if f.frame_id == cm.frame_id]
    t0 = frames[0].timestamp
    keep = [f for f in mine if 1 <= round(f.timestamp - t0, 9) <= 5]
    (accel,), (gear,) = (ax.get_lines() for ax in fig.axes)
    assert accel.get_label() == "autocar_speed_command.accel_cmd [m/s²]"
    np.testing.assert_allclose(accel.get_xdata(), [f.timestamp - t0 for f in keep], atol=1e-6)
    assert list(accel.get_ydata()) == [cm.decode(f.data, decode_choices=False)["accel_cmd"] for f in keep]
    assert list(gear.get_ydata()) == [cm.decode(f.data, decode_choices=False)["gear_cmd"] for f in keep]
    assert gear.get_drawstyle() == "steps-post"
    ticks = {t.get_text() for t in fig.axes[1].get_yticklabels()}
    assert {str(v) for v in cm.get_signal_by_name("gear_cmd").choices.values()} <= ticks
    plt.close("all")


def test_unknown_signal_and_missing_log(drive):
    log, _ = drive
    proc = subprocess.run(
        [sys.executable, "-m", "canspec", "plot", str(log), "no_such_*", "-o", "x.png"], capture_output=True, text=True, env=CANSPEC_ENV, check=False
    )
    assert proc.returncode == 2 and "no signal matches 'no_such_*'" in proc.stderr and "Traceback" not in proc.stderr
    proc = subprocess.run([sys.executable, "-m", "canspec", "plot", "missing.blf", "accel_cmd"], capture_output=True, text=True, env=CANSPEC_ENV, check=False)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr


def _plot(*args):
    return subprocess.run([sys.executable, "-m", "canspec", "plot", *map(str, args)], capture_output=True, text=True, env=CANSPEC_ENV, check=False, timeout=120)


@pytest.mark.parametrize(("args", "says"), [
    (["--dpi", "100000"], "argument --dpi: 100000 is not in 1..600"),  # was std::bad_alloc, an internal error
    (["--dpi", "0"], "argument --dpi: 0 is not in 1..600"),
    (["--start", "nan"], "argument --start: nan is not a finite number"),  # was an empty plot, exit 0
    (["--stop", "inf"], "argument --stop: inf is not a finite number"),
    (["--start", "5", "--stop", "1"], "--start 5 is not before --stop 1: nothing to plot"),
])
def test_arguments_no_plot_can_have_are_refused(drive, tmp_path, args, says):
    log, _ = drive
    proc = _plot(log, "accel_*", "-o", tmp_path / "c.png", *args)
    assert proc.returncode == 2 and says in proc.stderr and "Traceback" not in proc.stderr, proc.stderr
    assert not (tmp_path / "c.png").exists()


def test_a_window_without_frames_and_an_image_too_large_are_refused(drive, tmp_path):
    """A window past the log's end would be an empty plot (a dead bus, to the reader); one panel
    per signal at 600 dpi is more pixels than the renderer can allocate."""
    log, _ = drive
    proc = _plot(log, "accel_*", "-o", tmp_path / "c.png", "--start", "1000")
    assert proc.returncode == 1 and "the chosen signals have no frame from 1000 s to the end of the logs" in proc.stderr, proc.stderr
    proc = _plot(log, "*", "--stack", "-o", tmp_path / "c.png", "--dpi", "600")
    assert proc.returncode == 2 and "pixel image at --dpi 600 is more than 50,000,000 pixels (hint: a lower --dpi" in proc.stderr, proc.stderr
    assert "Traceback" not in proc.stderr and not (tmp_path / "c.png").exists()


def test_an_output_without_an_image_extension_is_refused_and_a_failed_write_keeps_the_old_file(drive, tmp_path):
    """`-o e` wrote `e.png` (matplotlib appends its default format): the name the user gave is now
    refused with the formats it may end in. A write into a directory that is not there fails with
    the path, and an existing image is replaced only by a whole new one (no temporary left)."""
    log, _ = drive
    proc = _plot(log, "accel_*", "-o", tmp_path / "e", "--dpi", "50")
    assert proc.returncode == 2 and "e: name the image format by the file's extension (" in proc.stderr and ".png" in proc.stderr, proc.stderr
    assert list(tmp_path.iterdir()) == []
    proc = _plot(log, "accel_*", "-o", tmp_path / "missing" / "p.png", "--dpi", "50")
    assert proc.returncode == 2 and "cannot write" in proc.stderr and "Traceback" not in proc.stderr, proc.stderr
    old = tmp_path / "p.png"
    old.write_bytes(b"old")
    assert _plot(log, "accel_*", "-o", old, "--dpi", "50").returncode == 0
    assert old.read_bytes().startswith(b"\x89PNG") and [p.name for p in tmp_path.iterdir()] == ["p.png"]
