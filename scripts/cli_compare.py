#!/usr/bin/env python3
"""Byte-identity of two specseg programs' command lines (e.g. before and after a change to cli/).

    scripts/cli_compare.py REF_BIN NEW_BIN [--real | --real-only] [--jobs N] [--list] [--only CMD,...]

Runs every generated invocation with both programs, each in the same empty scratch folder, and
compares the exit code, stdout, stderr and the files written (names and bytes). The invocations:
every option of every command (and eval's modes, eval merge, the batch options) with valid, invalid,
missing, empty and out-of-range values, in both forms (--opt V, --opt=V), flags given a value, unknown
options, repeated options, surplus positional arguments, -h / --help anywhere, --json with usage
errors; on missing input files, so that nothing heavy runs. --real adds runs on the demo's shapes
(`NEW_BIN demo` output) and a small mesh. Timings ("timing: ...", "1.23 s" as in a batch's summary line,
JSON "seconds" and "t_*") are masked before comparing; prepared shapes (.sss) are compared by name only
(they differ from run to run of one program). A batch of several meshes on several threads may print
its per-mesh errors in another order from run to run: such a difference is not the change's. Prints the invocations that differ; exit 1 if any does.
"""
import argparse
import hashlib
import os
import re
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

INT_BAD = ["abc", "1.5", "3x", " 3", "0x10", "99999999999999999999", "-99999999999999999999", "+5", "-0"]
DBL = ["0", "-1", "0.5", "1e6", "1.000001e6", "1e7", "nan", "inf", "-inf", "1e308", "1.5e308", "-1.5e308", "1e-400",
       "abc", "0x1p3", "3.", "1e", "-0"]
STR = ["out.txt", "-", "dir/", "--help", "-h"]
SEED = ["0", "1", "18446744073709551615", "18446744073709551616", "-1", "abc", "1.5", "+3", " 3"]
SHARD = ["1/1", "3/8", "0/1", "2/1", "1/0", "a/b", "1/2x", "1", "1/-1", " 1/2", "2/3 "]
WXH = ["100x200", "16x16", "15x16", "16x8192", "16x4096", "16x4097", "16x8193", "100", "x100", "100x", "axb",
       "100X200", "100x200x3", "100x" + "0" * 60 + "100"]
SUFFIX = [".npy", "npy", ".a/b", ".labels.txt", ".x", "."]


def I(lo, hi):
    return [str(lo), str(hi), str(lo - 1), str(hi + 1)] + INT_BAD


def C(*words):
    return list(words) + ["x", words[0].upper(), words[0] + " ", words[0][:-1]]


F = None  # a flag
S2 = "two values"
BATCH = {"--jobs": I(1, 256), "--json": F, "--suffix": SUFFIX}

COMMANDS = {
    "info": ({"-o": STR, **BATCH}, [[], ["nomesh.off"], ["nomesh.off", "nomesh2.off"]]),
    "eigs": ({"-k": I(1, 2147483647), "-o": STR, "--evecs": STR, "--mass": C("barycentric", "voronoi"), "--sigma": DBL,
              **BATCH}, [[], ["nomesh.off"], ["nomesh.off", "-k", "5"]]),
    "descriptors": ({"--wks": F, "--hks": F, "-o": STR, "-k": I(3, 2147483647), "-n": I(1, 10000), **BATCH},
                    [[], ["nomesh.off"], ["nomesh.off", "--wks", "-o", "d.npy"], ["nomesh.off", "--hks"]]),
    "smooth": ({"-o": STR, "--steps": I(0, 100000), "--dt": DBL, "--bbox": F, **BATCH},
               [[], ["nomesh.off"], ["nomesh.off", "-o", "s.off"]]),
    "remesh": ({"-o": STR, "--faces": I(4, 2000000), "--iterations": I(1, 1000), **BATCH},
               [[], ["nomesh.off"], ["nomesh.off", "-o", "r.off"]]),
    "segment": ({"-o": STR, "--output": STR, "--centers": STR, "--ply": STR, "--faces": I(4, 2000000),
                 "--no-streamline": F, "--timings": F, **BATCH}, [[], ["nomesh.off"], ["nomesh.off", "-o", "l.txt"]]),
    "geodesic": ({"-s": I(0, 2147483647), "--source": I(0, 2147483647), "--method": C("exact", "graph", "edge"),
                  "--max-dist": DBL, "-o": STR, "--output": STR},
                 [[], ["nomesh.off"], ["nomesh.off", "-s", "0"], ["nomesh.off", "-s", "1", "-o", "d.txt"]]),
    "prepare": ({"-o": STR, "--output": STR, "-k": I(3, 10000), "--faces": I(4, 2000000), "--no-streamline": F,
                 "--no-signature": F}, [[], ["nomesh.off"], ["nomesh.off", "-o", "p.sss"]]),
    "match": ({"--landmarks": STR, "-o": STR, "--output": STR, "--fmap": STR, "--pairs": STR,
               "--probes": C("std", "asa", "diff"), "--segment-profile": C("indicator", "tent", "soft"),
               "--k": I(3, 10000), "--zoomout": I(3, 10000), "--no-refine": F, "--descr-k": I(3, 10000),
               "--zoomout-step": I(1, 10000), "--zoomout-samples": I(0, 1000000000), "--orient": DBL, "--timings": F,
               "--descriptors": S2, "--no-wks": F, "--json": F, "--hypotheses": I(1, 8)},
              [[], ["nx.off"], ["nx.off", "ny.off"], ["nx.off", "ny.off", "-o", "map.txt"]]),
    "pair": ({"-o": STR, "--output": STR, "--timings": F}, [[], ["nx.off"], ["nx.off", "ny.off"]]),
    "error": ({"--gt": STR, "--sym": STR, "--x": STR, "-o": STR, "--json": F},
              [[], ["nomap.txt"], ["nomap.txt", "ny.off"]]),
    "demo": ({"-o": STR + ["demo-out"]}, [["extra"]]),
    "render": ({"--labels": STR, "--scalar": STR, "--map": STR, "--error": STR, "--centers": STR, "--landmarks": STR,
                "-o": STR, "--output": STR, "--target": STR, "--gt": STR, "--sym": STR, "--match-colors": STR,
                "--view": ["front", "back", "left", "right", "top", "bottom", "10,20", "10,91", "10,-90", "a,b", "10",
                           "nan,0", "inf,0", "10,20,30", "FRONT"],
                "--size": WXH, "--isolines": I(0, 1000), "--cols": I(1, 64), "--supersample": I(1, 4),
                "--range": ["0,1", "1,0", "1,1", "a,1", "1", "0,inf", "-1,1", "nan,1", "1e400,2", "0," + "9" * 200],
                "--no-titles": F, "--up": C("auto", "x", "y", "z", "+x", "+y", "+z", "-x", "-y", "-z"),
                "--scale": C("fit", "common")},
               [[], ["nomesh.off"], ["nomesh.off", "-o", "r.png"]]),
    "eval": ({"--table1": F, "--coherency": F, "--timings": F, "--quiet": F, "--gallery-only": F, "--json": F,
              "--figures": STR, "--data": STR, "--out": STR, "-o": STR, "--cache": STR, "--manifest": STR,
              "--gallery-count": I(0, 100), "--candidates": I(1, 100),
              "--pair": ["1,2", "1,1", "0,99", "100,1", "a,b", "12", "-1,3", "1,2,3", "1, 2"],
              "--size": WXH, "--pairs": I(1, 900), "--jobs": I(1, 1024), "--k": I(3, 1000), "--shapes": I(1, 100),
              "--error-samples": I(0, 3000), "--seed": SEED, "--shard": SHARD,
              "--policies": ["random", "subj,pose", "x", "random,x", ",", "random,,pose"],
              "--landmarks": ["best", "gt,fps", "none", "x"], "--methods": ["std", "asa,diff,refined", "x"],
              "--pairing": C("paper", "confident")},
             [[], ["--table1"], ["--table1", "--data", "nodata"], ["--figures", "figs", "--data", "nodata"],
              ["--coherency", "--manifest", "nomanifest"]]),
}
# eval's other modes: (prefix, options, bases)
MODES = {
    "eval --benchmark": (["eval", "--benchmark", "nobench"],
                         {"--out": STR, "-o": STR, "--pairs": STR, "--cache": STR, "--title": STR,
                          "--max-pairs": I(1, 2000000000), "--seed": SEED,
                          "--landmarks": ["none", "gt:1", "gt:64", "gt:65", "gt:0", "gt:", "gt:x", "x", "GT:1"],
                          "--maps": ["a=b", "=b", "a=", "ab", "a=b=c"], "--no-match": F, "--quiet": F, "--json": F,
                          "--jobs": I(1, 1024), "--shard": SHARD}, [[], ["--no-match"]]),
    "eval merge": (["eval", "merge"], {"--out": STR, "-o": STR, "--manifest": STR}, [[], ["nocsv.csv"]]),
    "eval merge (benchmark)": (["eval", "merge", "BENCHCSV"], {"--out": STR, "-o": STR, "--title": STR, "--json": F},
                               [[], ["nocsv.csv"]]),
}


def option_cases(opts, bases):
    """every option: each value in both forms, missing / empty values, flags given a value, twice"""
    out = []
    for name, vals in opts.items():
        if vals is F:
            forms = [[name], [name + "=1"], [name + "="], [name, name]]
        elif vals is S2:
            forms = [[name, "a.npy", "b.npy"], [name + "=a.npy", "b.npy"], [name, "a.npy"], [name], [name + "="],
                     [name, "", "b.npy"], [name, "a.npy", ""], [name, "-", "b.npy"]]
        else:
            forms = []
            for v in vals:
                forms += [[name, v], [name + "=" + v]]
            forms += [[name], [name + "="], [name, ""], [name, vals[0], name, vals[-1]], [name, vals[-1], name, vals[0]],
                      [name, vals[0], "--bogus"]]
        for b in bases:
            for f in forms:
                out.append(b + f)
                if b is bases[-1]:
                    out.append(f + b)
    return out


def generic_cases(bases, has_json):
    out = []
    for b in bases:
        for extra in (["--help"], ["-h"], ["--bogus"], ["-x"], ["--bogus=1"], ["-"], ["p1", "p2", "p3"], ["--"],
                      ["-o", "--help"], ["--he"], ["--HELP"], ["---o"], ["-" + "o" * 100]):
            out.append(b + extra)
            out.append(extra + b)
        if has_json:
            for extra in (["--json", "--bogus"], ["--bogus", "--json"], ["--json=1"], ["--json", "-"]):
                out.append(b + extra)
    return out


def invocations(only=None):
    inv = []
    for cmd, (opts, bases) in COMMANDS.items():
        if only is not None and cmd not in only:
            continue
        json = "--json" in opts
        for args in option_cases(opts, bases) + generic_cases(bases, json):
            inv.append([cmd] + args)
            if json and "--json" not in args and args[:len(bases[-1])] == bases[-1]:
                inv.append([cmd] + args + ["--json"])
        inv.append(["help", cmd])
    for mode, (prefix, opts, bases) in MODES.items():
        if only is not None and mode not in only:
            continue
        json = "--json" in opts
        for args in option_cases(opts, bases) + generic_cases(bases, json):
            inv.append(prefix + args)
    if not only:
        inv += [[], ["help"], ["--help"], ["-h"], ["help", "nocmd"], ["help", "a", "b"], ["version"], ["--version"],
                ["version", "x"], ["nocmd"], ["-x"]]
    return inv


def real_invocations(d, small):
    """runs on the demo's shapes (d) and a small mesh"""
    sp, to, h0, h2 = (os.path.join(d, n) for n in ("sphere.off", "torus.off", "humanoid_pose0.off", "humanoid_pose2.off"))
    mp = os.path.join(d, "map_humanoid_pose0_to_humanoid_pose2.txt")
    return [
        ["info", sp], ["info", to, small, "--json"], ["info", d, "-o", "infos/"], ["info", small, "-o", "i.txt"],
        ["info", h0, "--jobs", "1"],
        ["eigs", sp, "-k", "6"], ["eigs", small, "-k", "3", "--mass", "voronoi", "--sigma", "0"],
        ["eigs", sp, "-k", "4", "-o", "e.npy", "--evecs", "v.npy", "--json"], ["eigs", sp, to, "-k", "3", "-o", "E"],
        ["eigs", small, "-k", "50"],
        ["descriptors", sp, "--wks", "-k", "10", "-n", "5", "-o", "w.npy"], ["descriptors", to, "--hks", "-k", "8", "-o", "-"],
        ["descriptors", sp, to, "--hks", "-o", "D", "--suffix", ".h.npy", "--json"],
        ["smooth", sp, "-o", "s.off", "--steps", "2"], ["smooth", to, "-o", "-", "--steps", "1", "--bbox"],
        ["smooth", sp, "-o", "s.ply", "--dt", "1e-4", "--bbox", "--steps", "1"], ["smooth", sp, to, "-o", "S", "--steps", "1"],
        ["remesh", sp, "-o", "r.off", "--faces", "500", "--iterations", "2"], ["remesh", to, "-o", "R/", "--faces", "300", "--json"],
        ["segment", sp, "-o", "l.txt", "--centers", "c.txt", "--ply", "s.ply", "--timings"],
        ["segment", h0, "-o", "-", "--faces", "3000"], ["segment", to, "-o", "l.txt", "--no-streamline", "--json"],
        ["segment", sp, to, "-o", "L", "--ply", ".ply", "--jobs", "2"],
        ["geodesic", sp, "-s", "0", "-s", "5", "-o", "g.txt"], ["geodesic", to, "--source", "3", "--method", "graph", "-o", "-"],
        ["geodesic", sp, "-s", "0", "--method", "edge", "--max-dist", "0.5", "-o", "g.npy"], ["geodesic", sp, "-s", "99999", "-o", "g.txt"],
        ["prepare", sp, "-o", "p.sss", "-k", "20", "--faces", "2000"], ["prepare", small, "-o", "q.sss", "--no-signature", "-k", "3"],
        ["match", h0, h2, "-o", "m.txt", "--json"], ["match", h0, h2, "-o", "m.txt", "--probes", "std", "--k", "20",
                                                      "--zoomout", "30", "--timings"],
        ["match", sp, sp, "-o", "-", "--no-refine", "--k", "10", "--landmarks", os.path.join(d, "lm.txt")],
        ["pair", h0, h2, "-o", "pairs.txt"], ["pair", h0, h2, "--timings", "-o", "-"],
        ["error", mp, h2], ["error", mp, h2, "--x", h0, "-o", "e.txt", "--json"], ["error", mp, h2, "--gt", mp, "-o", "-"],
        ["render", sp, "-o", "r.png", "--size", "64x64", "--supersample", "1"],
        ["render", h0, "--map", mp, "--target", h2, "-o", "m.png", "--size", "48x48", "--view", "10,20", "--up", "y"],
        ["render", sp, to, "-o", "two.png", "--size", "32x40", "--cols", "1", "--no-titles", "--scale", "common"],
        ["demo", "-o", "demo2"],
    ]


def snapshot(root):
    files = {}
    for dp, _, fns in os.walk(root):
        for fn in fns:
            p = os.path.join(dp, fn)
            with open(p, "rb") as f:
                files[os.path.relpath(p, root)] = "sss" if p.endswith(".sss") else hashlib.sha256(f.read()).hexdigest()
    return files


MASKS = [(re.compile(rb"(timing: \S+ )[0-9.e+-]+"), rb"\1T"), (re.compile(rb"[0-9]+\.[0-9]+ s\b"), rb"T s"),
         (re.compile(rb'("(?:seconds|t_[a-z_]+)": )[0-9.e+-]+'), rb"\1T")]


def run(binary, args, cwd, mask):
    for n in os.listdir(cwd):
        p = os.path.join(cwd, n)
        shutil.rmtree(p) if os.path.isdir(p) else os.remove(p)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    r = subprocess.run([binary] + args, cwd=cwd, stdin=subprocess.DEVNULL, capture_output=True, env=env, timeout=600)
    out, err = r.stdout, r.stderr
    for rx, rep in MASKS:  # timings: real runs, and every batch's summary line
        out, err = rx.sub(rep, out), rx.sub(rep, err)
    return r.returncode, out, err, snapshot(cwd)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("ref")
    ap.add_argument("new")
    ap.add_argument("--real", action="store_true", help="also real runs on the demo's shapes")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--list", action="store_true", help="print the invocations only")
    ap.add_argument("--real-only", action="store_true", help="only the real runs")
    ap.add_argument("--only", help="these commands (or eval modes: 'eval merge', ...) only, comma-separated")
    a = ap.parse_args()
    ref, new = os.path.abspath(a.ref), os.path.abspath(a.new)
    tmp = tempfile.mkdtemp(prefix="cli_compare.")
    fix = os.path.join(tmp, "fixtures")
    os.makedirs(fix)
    bench = os.path.join(fix, "bench_pairs.csv")
    with open(bench, "w") as f:
        f.write("method,x,y,error\n")
    only = a.only.split(",") if a.only else None
    cases = [] if a.real_only else [[bench if x == "BENCHCSV" else x for x in c] for c in invocations(only)]
    masked = set()
    if a.real or a.real_only:
        d = os.path.join(fix, "demo")
        subprocess.run([new, "demo", "-o", d], capture_output=True, check=True)
        with open(os.path.join(d, "lm.txt"), "w") as f:
            f.write("0\n100\n200\n300\n")
        small = os.path.join(fix, "tetra.off")
        with open(small, "w") as f:
            f.write("OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 2 1\n0 1 3\n0 3 2\n1 2 3\n")
        real = real_invocations(d, small)
        masked = set(range(len(cases), len(cases) + len(real)))
        cases += real
    if a.list:
        for c in cases:
            print(" ".join(c))
        return 0

    def one(i):
        w = os.path.join(tmp, "w%d" % (i % (4 * a.jobs)))
        os.makedirs(w, exist_ok=True)
        return i, run(ref, cases[i], w, i in masked), run(new, cases[i], w, i in masked)

    # one scratch folder per slot: never two invocations in one at the same time
    slots = 4 * a.jobs
    differ = 0
    with ThreadPoolExecutor(a.jobs) as ex:
        results = []
        for batch in range(0, len(cases), slots):
            results = list(ex.map(one, range(batch, min(batch + slots, len(cases)))))
            differ += report(cases, results)
    print("%d invocations (%d real runs, timings masked), %d differ" % (len(cases), len(masked), differ))
    shutil.rmtree(tmp, ignore_errors=True)
    return 1 if differ else 0


def report(cases, results):
    """prints the invocations whose results differ; how many"""
    differ = 0
    for i, r, n in results:
        if r != n:
            differ += 1
            print("DIFFER: specseg %s" % " ".join(repr(x) if not x or " " in x else x for x in cases[i]))
            for what, x, y in zip(("exit", "stdout", "stderr", "files"), r, n):
                if x != y:
                    print("  %s: %r\n  %s  %r" % (what, x if what != "files" else sorted(x.items()), " " * len(what),
                                                  y if what != "files" else sorted(y.items())))
    sys.stdout.flush()
    return differ


if __name__ == "__main__":
    sys.exit(main())
