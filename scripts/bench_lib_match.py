#!/usr/bin/env python3
"""CPU of a landmark-free match of two prepared shapes through the library, as a program or the
Python package calls it (the allocator's own settings: unlike the CLI, nothing raises glibc's mmap
threshold), with two builds of libspecseg side by side: rounds interleaved (the order rotates),
one thread each, medians printed with their ratio and the page faults of each.

  scripts/bench_lib_match.py REF_LIB NEW_LIB X1.sss Y1.sss [X2.sss Y2.sss ...] [--rounds R]

REF_LIB, NEW_LIB: libspecseg.so files (or folders holding one); REF_LIB is the reference. Each match
runs in its own Python process (the package binds one library per process, $SPECSEG_LIB), timed with
time.process_time() around specseg.match(X, Y) alone (reading the shapes not timed).
"""
import os, statistics, subprocess, sys

CHILD = r"""
import resource, sys, time
import specseg
X, Y = specseg.Shape.load(sys.argv[1]), specseg.Shape.load(sys.argv[2])
f0, t0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt, time.process_time()
specseg.match(X, Y)
print(time.process_time() - t0, resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0)
"""


def main(argv):
    rounds = 3
    if "--rounds" in argv:
        i = argv.index("--rounds")
        rounds = int(argv[i + 1])
        del argv[i:i + 2]
    if len(argv) < 4 or len(argv) % 2:
        sys.exit(__doc__)
    libs = {"reference": argv[0], "new": argv[1]}
    pairs = list(zip(argv[2::2], argv[3::2]))
    here = os.path.dirname(os.path.abspath(__file__))
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1",
               PYTHONPATH=os.path.join(here, "..", "python") + os.pathsep + os.environ.get("PYTHONPATH", ""))
    cpu = {(n, p): [] for n in libs for p in pairs}
    flt = {(n, p): [] for n in libs for p in pairs}
    for r in range(rounds):
        order = list(libs) if r % 2 == 0 else list(reversed(list(libs)))
        for name in order:
            for p in pairs:
                out = subprocess.run([sys.executable, "-c", CHILD, p[0], p[1]], check=True, capture_output=True,
                                     text=True, env=dict(env, SPECSEG_LIB=libs[name])).stdout.split()
                cpu[(name, p)].append(float(out[0]))
                flt[(name, p)].append(int(out[1]))
    for p in pairs:
        ref, new = (statistics.median(cpu[(n, p)]) for n in ("reference", "new"))
        print("%s -> %s: reference %.2f s CPU (%d page faults), new %.2f s CPU (%d page faults), ratio %.2fx" % (
            os.path.basename(p[0]), os.path.basename(p[1]), ref, statistics.median(flt[("reference", p)]), new,
            statistics.median(flt[("new", p)]), ref / new))


if __name__ == "__main__":
    main(sys.argv[1:])
