"""`make bench-c-cross`: canspec's generated C against `cantools generate_c_source` on the
generated DBC, on the exact Cortex-M0+ and Cortex-M4 cores (arm-none-eabi-gcc), per core and
optimisation level: dynamic instructions of pack + unpack per message, code size, stack, and the
libgcc / libc helpers the code calls. x86-64 stays in tests/targets/c/bench.py (callgrind).

Dynamic instructions: every library is compiled into its own translation units with the core's
flags plus -ffunction-sections -fno-ipa-icf (canspec's static inline pack/unpack behind extern
wrappers, as bench.py's call mode; cantools' .c as it ships; "cantools+user" (like for like):
extern wrappers in the user's translation unit that add what canspec does and cantools does not
-- check the XOR checksum before cantools' unpack and fill it after its pack, byte-wise, on the
messages that carry one, and refuse a field that does not fit its bits before cantools' pack,
which would drop the excess bits silently (range_checks: the same compares as canspec's)). A harness function per (library,
message, pack|unpack) calls the function on the same 16 frames per message (bench.py's
frames_for: the shared vectors, cycled). The ELF runs once under
`qemu-arm -singlestep -d exec,nochain`, which logs every executed instruction's address; an
instruction is counted for a harness function when it executes while that harness function is
active (entered and not yet returned to main) but lies outside the harness function's own code:
i.e. exactly the instructions of the called functions and of everything they call (helpers
included), without the harness's loop and call set-up. The harness then checks that all three
libraries returned 0 and packed the input frames back byte for byte (same work on both sides).

Size: nm sizes of the functions in question plus the static helpers of the same object that they
call (the call graph from the linked disassembly), and the read-only data they read where it is
not in their literal pools (canspec's double encoders' `_phys` descriptors); libgcc / libc
helpers are listed by name.
The physical-value API is measured on a translation unit that takes the address of each
canspec function (so each is emitted once, out of line): the double path against cantools'
default `_encode`/`_decode`, the integer path against what `--no-floating-point-numbers` leaves.
Stack: gcc -fstack-usage frames, and the deepest call path (frames added along the call graph;
functions without a .su entry, i.e. libgcc/libc, estimated from their push/sub sp prologue).

    python3 tests/targets/c/cross/bench_cross.py [--headers DIR] [--dbc FILE] [--vectors FILE] [--spec SPEC]
        [--configs cortex-m0plus:-Os,cortex-m4:-Os,...] [--build DIR] [-j N]
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))
import cbuild  # noqa: E402
import cross  # noqa: E402
from bench import FRAMES_PER_MESSAGE  # noqa: E402
from bench_sources import LIBS, PHASES, Inputs, load_inputs, write_sources  # noqa: E402
from elf_image import Image, deepest, group_size, is_helper, load_image, stack_usage, trace_counts  # noqa: E402

ROOT = cbuild.ROOT
DEFAULT_CONFIGS = "cortex-m0plus:-Os,cortex-m0plus:-O2,cortex-m4:-Os,cortex-m4:-O2"
COMMON = ["-std=gnu99", "-ffunction-sections", "-fno-ipa-icf", "-fstack-usage"]
# The translation units write_sources writes besides cantools' own .c files.
UNITS = ("canspec_wrappers", "cantools_xor", "cantools_xoronly", "harness_canspec", "harness_cantools", "harness_cantools_xor", "bench_main",
         "canspec_api", "stub_main", "stub_main_api")


# --- build and measure --------------------------------------------------------------------


@dataclass
class ConfigResult:
    core: str
    opt: str
    counts: dict[tuple[str, str, str], float] = field(default_factory=dict)  # (lib, msg, phase) → instr per call
    traced_helpers: dict[str, set[str]] = field(default_factory=dict)  # lib → helpers executed
    check: str = ""
    sizes: dict[str, tuple[int, set[str]]] = field(default_factory=dict)
    stack: dict[str, tuple[int, list[str]]] = field(default_factory=dict)
    frame: dict[str, tuple[int, str]] = field(default_factory=dict)
    seconds: float = 0.0
    error: str = ""


def compile_obj(core: str, opt: str, src: Path, obj: Path, inc: list[Path]) -> None:
    cmd = [cross.ARM_CC, *cross.ARM_CORES[core], opt, *COMMON, *[f"-I{p}" for p in inc], "-c", str(src), "-o", str(obj)]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}\n{proc.stderr[-4000:]}")


def link(core: str, objs: list[Path], exe: Path, shim_dir: Path) -> None:
    target = cross.Target(f"bench-{core}", cross.ARM_CC, cross.ARM_CORES[core], ("qemu-arm",), bare_metal=True)
    cmd = [cross.ARM_CC, *cross.ARM_CORES[core], *map(str, objs), "-o", str(exe), *cross.link_flags(target, shim_dir)]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}\n{proc.stderr[-4000:]}")


def measure(inp: Inputs, build: Path, ct: Path, ct_nofp: Path, core: str, opt: str) -> ConfigResult:
    res = ConfigResult(core, opt)
    t0 = time.monotonic()
    out = build / f"{core}{opt}"
    out.mkdir(parents=True, exist_ok=True)
    for su in out.glob("*.su"):
        su.unlink()
    try:
        objs = _compile_all(inp, build, ct, ct_nofp, core, opt, out)
        _count(inp, build, core, objs, out / "bench.elf", res)
        images = _size_images(build, core, objs, out)
        groups = _groups(inp, images)
        _sizes(inp, images, groups, res)
        _stacks(images, groups, out, res)
    except (RuntimeError, subprocess.CalledProcessError, OSError) as exc:
        res.error = str(exc)
    res.seconds = time.monotonic() - t0
    return res


def _compile_all(inp: Inputs, build: Path, ct: Path, ct_nofp: Path, core: str, opt: str, out: Path) -> dict[str, Path]:
    """Every translation unit as an object of this core and level. The two libraries' umbrella
    headers may share a name: each translation unit sees one."""
    objs = {}
    for name in UNITS:
        compile_obj(core, opt, build / f"{name}.c", out / f"{name}.o", [ct] if "cantools" in name else [inp.headers])
        objs[name] = out / f"{name}.o"
    for name, src, inc in (("cantools", ct / f"{inp.db}.c", ct), ("cantools_nofp", ct_nofp / f"{inp.db}.c", ct_nofp),
                           ("cantools_fixed_user", build / "cantools_fixed_user.c", ct_nofp)):
        compile_obj(core, opt, src, out / f"{name}.o", [inc])
        objs[name] = out / f"{name}.o"
    return objs


def _count(inp: Inputs, build: Path, core: str, objs: dict[str, Path], bench: Path, res: ConfigResult) -> None:
    """The dynamic count: every harness function in one traced run."""
    link(core, [objs[n] for n in ("bench_main", "harness_canspec", "harness_cantools", "harness_cantools_xor", "canspec_wrappers", "cantools_xor",
                                  "cantools")], bench, build)
    run_names = {f"run_{lib}_{n}_{ph}" for lib in LIBS for n in inp.names for ph in PHASES}
    counts, seen, res.check = trace_counts(bench, run_names)
    for lib in LIBS:
        helpers: set[str] = set()
        for n in inp.names:
            for ph in PHASES:
                key = f"run_{lib}_{n}_{ph}"
                res.counts[(lib, n, ph)] = counts.get(key, 0) / FRAMES_PER_MESSAGE
                helpers |= {s for s in seen.get(key, ()) if is_helper(s)}
        res.traced_helpers[lib] = helpers


def _size_images(build: Path, core: str, objs: dict[str, Path], out: Path) -> dict[str, Image]:
    """Single-library images, for sizes, helpers and stack."""
    images = {}
    for name, units in {"canspec": ["canspec_wrappers", "stub_main"],
                        "cantools": ["cantools", "stub_main"],
                        "cantools_xor": ["cantools", "cantools_xor", "stub_main"],
                        "cantools_xoronly": ["cantools", "cantools_xoronly", "stub_main"],
                        "cantools_nofp": ["cantools_nofp", "stub_main"],
                        "cantools_fixed_user": ["cantools_nofp", "cantools_fixed_user", "stub_main"],
                        "api": ["canspec_api", "stub_main_api"]}.items():
        link(core, [objs[u] for u in units], out / f"size_{name}.elf", build)
        images[name] = load_image(out / f"size_{name}.elf")
    return images


def _api_patterns(inp: Inputs) -> dict[str, str]:
    """canspec's physical-value and monitor functions, by the C names of the messages measured."""
    p = re.escape(inp.prefix)
    cmsgs = "|".join(re.escape(inp.c_base[n]) for n in inp.names)
    return {"double": rf"{p}_({cmsgs})_\w+_(encode|decode)", "fixed": rf"{p}_({cmsgs})_\w+_(encode|decode)_fixed",
            "monitor": rf"{p}_monitor_(on_frame|check)", "phys": rf"{p}_({cmsgs})_\w+_phys(\.\d+)?"}


def _groups(inp: Inputs, images: dict[str, Image]) -> dict[str, tuple[str, list[str]]]:
    """label → (image, the functions whose size is counted)."""
    api, db = _api_patterns(inp), re.escape(inp.db)
    msgs = "|".join(map(re.escape, inp.names))  # cantools' names: the spec's

    def matching(img: str, pattern: str) -> tuple[str, list[str]]:
        return img, [f for f in images[img].sizes if re.fullmatch(pattern, f)]

    def wrapped(img: str, stem: str) -> tuple[str, list[str]]:
        """The user's wrappers where the message has one, else the cantools function they would call."""
        return img, [f"{stem}_{n}_{ph}" if f"{stem}_{n}_{ph}" in images[img].sizes else f"{inp.db}_{n}_{ph}" for n in inp.names for ph in PHASES]

    return {
        "canspec pack+unpack": ("canspec", [f"x_{n}_{ph}" for n in inp.names for ph in PHASES]),
        "cantools pack+unpack": ("cantools", [f"{inp.db}_{n}_{ph}" for n in inp.names for ph in PHASES]),
        "cantools+XOR pack+unpack": wrapped("cantools_xoronly", "cxo"),
        # like for like: the user's XOR and range-check wrappers with the cantools functions they call
        "cantools+user pack+unpack": wrapped("cantools_xor", "cx"),
        "canspec double encode+decode": matching("api", api["double"]),
        "cantools double encode+decode": matching("cantools", rf"{db}_({msgs})_\w+_(encode|decode)"),
        "cantools is_in_range+is_in_phys_range": matching("cantools", rf"{db}_({msgs})_\w+_is_in_(phys_)?range"),
        "canspec integer encode+decode_fixed": matching("api", api["fixed"]),
        "cantools --no-floating-point-numbers is_in_range": matching("cantools_nofp", rf"{db}_({msgs})_\w+_is_in_range"),
        # like for like: cantools converts nothing without floats; the user's conversion around its is_in_range (fixed_user.py)
        "cantools+user integer (conversion + is_in_range)": matching("cantools_fixed_user", r"ux_\w+_(en|de)code_fixed"),
        "cantools --no-floating-point-numbers is_in_phys_range (double)": matching("cantools_nofp", rf"{db}_({msgs})_\w+_is_in_phys_range"),
        "canspec monitor on_frame+check": matching("api", api["monitor"]),
    }


def _sizes(inp: Inputs, images: dict[str, Image], groups: dict[str, tuple[str, list[str]]], res: ConfigResult) -> None:
    # read-only data a group's functions read, by name: the double encoders' descriptors
    # (file scope, or `<name>.<n>` where GCC names an encoder's own)
    data = {"canspec double encode+decode": _api_patterns(inp)["phys"]}
    for label, (img, roots) in groups.items():
        res.sizes[label] = group_size(images[img], roots) if roots else (0, set())
        if label in data:
            extra = sum(n for name, n in images[img].data.items() if re.fullmatch(data[label], name))
            res.sizes[label] = (res.sizes[label][0] + extra, res.sizes[label][1])


def _stacks(images: dict[str, Image], groups: dict[str, tuple[str, list[str]]], out: Path, res: ConfigResult) -> None:
    for label, img, obj, roots in (("canspec pack/unpack", "canspec", "canspec_wrappers", groups["canspec pack+unpack"][1]),
                                   ("cantools pack/unpack", "cantools", "cantools", groups["cantools pack+unpack"][1]),
                                   ("canspec monitor", "api", "canspec_api", groups["canspec monitor on_frame+check"][1])):
        su = stack_usage(out / f"{obj}.su")
        frames = [(su.get(f, images[img].frames.get(f, 0)), f) for f in roots]
        res.frame[label] = max(frames) if frames else (0, "-")
        paths = [deepest(images[img], su, f) for f in roots]
        res.stack[label] = max(paths, key=lambda d: d[0]) if paths else (0, [])


# --- report -------------------------------------------------------------------------------


def report(inp: Inputs, results: list[ConfigResult]) -> str:
    out: list[str] = []
    sizes_by_core: dict[str, dict[str, ConfigResult]] = {}
    for r in results:
        sizes_by_core.setdefault(r.core, {})[r.opt] = r
        out.append(f"\n[{r.core} {r.opt}] dynamic instructions per pack+unpack pair (qemu-arm -singlestep trace, "
                   f"{FRAMES_PER_MESSAGE} frames per message; ratio = other / canspec)")
        if r.error:
            out.append(f"FAILED: {r.error}")
            continue
        out.append(f"{'message':<28} {'canspec':>8} {'(unpack':>8} {'pack)':>6} {'cantools':>9} {'ratio':>6} {'cantools+user':>13} {'ratio':>6}")
        tot = {lib: 0.0 for lib in LIBS}
        worst: tuple[float, str] = (1e9, "-")
        for n in inp.names:
            v = {lib: r.counts[(lib, n, "unpack")] + r.counts[(lib, n, "pack")] for lib in LIBS}
            for lib in LIBS:
                tot[lib] += v[lib]
            rx = v["cantools_xor"] / v["canspec"] if v["canspec"] else 0.0
            worst = min(worst, (rx, n))
            out.append(f"{n:<28} {v['canspec']:8.1f} {r.counts[('canspec', n, 'unpack')]:8.1f} {r.counts[('canspec', n, 'pack')]:6.1f} "
                       f"{v['cantools']:9.1f} {v['cantools'] / v['canspec'] if v['canspec'] else 0:5.2f}x "
                       f"{v['cantools_xor']:13.1f} {rx:5.2f}x" + ("  *" if n in inp.xor else ""))
        out.append(f"{'overall (sum)':<28} {tot['canspec']:8.1f} {'':>8} {'':>6} {tot['cantools']:9.1f} {tot['cantools'] / tot['canspec']:5.2f}x "
                   f"{tot['cantools_xor']:13.1f} {tot['cantools_xor'] / tot['canspec']:5.2f}x")
        fewer = sum(r.counts[("canspec", n, "unpack")] + r.counts[("canspec", n, "pack")]
                    <= r.counts[("cantools_xor", n, "unpack")] + r.counts[("cantools_xor", n, "pack")] for n in inp.names)
        out.append(
            f"worst message (like for like): {worst[1]} {worst[0]:.2f}x; "
            f"canspec executes at most as many instructions as cantools+user on {fewer} of {len(inp.names)}"
            "  (* = XOR checksum message; cantools+user = cantools + the XOR fill/check + the field range check a user adds for canspec's guarantees; "
            f"{r.check})")
        for lib in LIBS:
            out.append(f"helpers executed by {lib}: {', '.join(sorted(r.traced_helpers[lib])) or 'none'}")
    for core, by_opt in sizes_by_core.items():
        opts = list(by_opt)
        out.append(f"\n[{core}] code size, bytes (-ffunction-sections -fno-ipa-icf: the functions + the static helpers they call; "
                   "libgcc/libc helpers named, not counted)")
        labels = next((list(r.sizes) for r in by_opt.values() if r.sizes), [])
        out.append(f"{'':<62}" + "".join(f"{o:>8}" for o in opts) + "  helpers called")
        for label in labels:
            row = [by_opt[o].sizes.get(label, (0, set())) for o in opts]
            helpers = sorted(set().union(*(h for _, h in row)))
            out.append(f"{label:<62}" + "".join(f"{s:>8}" for s, _ in row) + f"  {', '.join(helpers) or '-'}")
        out.append("stack, bytes (-fstack-usage; deepest path adds frames along the call graph)")
        for o in opts:
            r = by_opt[o]
            for label in r.frame:
                fr, fn = r.frame[label]
                depth, path = r.stack[label]
                out.append(f"  {o:<4} {label:<22} largest frame {fr:>4} ({fn}); deepest path {depth:>4}: {' > '.join(path)}")
    out.append("\nhelper-free (no libgcc/soft-float/libc call from pack/unpack and the integer path, by call graph):")
    for r in results:
        if r.error:
            continue
        found = sorted(r.sizes["canspec pack+unpack"][1] | r.sizes["canspec integer encode+decode_fixed"][1])
        out.append(f"  {r.core} {r.opt}: {'yes' if not found else 'NO: ' + ', '.join(found)}")
    return "\n".join(out)


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description="canspec C vs cantools on Cortex-M0+/M4 under qemu-arm")
    ap.add_argument("--headers", type=Path, default=cbuild.HEADERS)
    ap.add_argument("--dbc", type=Path, default=ROOT / "generated" / "dbc" / "kaiwo_gateway.dbc")
    ap.add_argument("--vectors", type=Path, default=cbuild.DEFAULT_VECTORS)
    ap.add_argument("--spec", type=Path, default=ROOT / "spec", help="the spec the headers came from (checksum layout)")
    ap.add_argument("--configs", default=DEFAULT_CONFIGS, help="core:opt,... with core in " + ", ".join(cross.ARM_CORES))
    ap.add_argument("--build", type=Path, default=ROOT / "build" / "c-bench-cross")
    ap.add_argument("-j", "--jobs", type=int, default=None)
    args = ap.parse_args(argv[1:])
    missing = [t for t in (cross.ARM_CC, "qemu-arm", "arm-none-eabi-nm", "arm-none-eabi-objdump") if not cross.shutil.which(t)]
    if missing:
        print(f"bench-c-cross: missing {', '.join(missing)} (make setup)", file=sys.stderr)
        return 1
    try:
        configs = [tuple(c.split(":", 1)) for c in args.configs.split(",") if c]
        for core, _ in configs:
            if core not in cross.ARM_CORES:
                raise ValueError(f"unknown core {core}")
        inp = load_inputs(args.headers, args.dbc, args.vectors, args.spec)
        ct, ct_nofp = write_sources(inp, args.build)
    except (ValueError, RuntimeError, OSError) as exc:
        print(f"bench-c-cross: {exc}", file=sys.stderr)
        return 1
    t0 = time.monotonic()
    with ThreadPoolExecutor(max_workers=args.jobs or os.cpu_count() or 2) as pool:
        results = list(pool.map(lambda c: measure(inp, args.build, ct, ct_nofp, c[0], c[1]), configs))
    print(f"{cross.ARM_CC} {' '.join(COMMON)}; cantools {inp.db}.c from {args.dbc.name}; {time.monotonic() - t0:.0f} s")
    print(report(inp, results))
    return 1 if any(r.error or not r.check.startswith("bench: 0 mismatches") for r in results) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
