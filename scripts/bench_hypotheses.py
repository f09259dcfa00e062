#!/usr/bin/env python3
"""CPU of a landmark-free match of two prepared shapes with the default hypotheses against one
hypothesis (the pairing's answer alone), run side by side: rounds interleaved, one thread each,
process CPU (user + system) of each `specseg match` measured with getrusage; medians printed with
their ratio.

  scripts/bench_hypotheses.py SPECSEG X1.sss Y1.sss [X2.sss Y2.sss ...] [--rounds R]
"""
import os, resource, statistics, subprocess, sys, tempfile


def cpu_of(cmd, env):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main(argv):
    rounds = 3
    if "--rounds" in argv:
        i = argv.index("--rounds")
        rounds = int(argv[i + 1])
        del argv[i:i + 2]
    if len(argv) < 3 or len(argv) % 2 == 0:
        sys.exit(__doc__)
    binary, shapes = argv[0], argv[1:]
    pairs = list(zip(shapes[0::2], shapes[1::2]))
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    out = os.path.join(tempfile.mkdtemp(), "map.txt")
    variants = [("default (4 hypotheses)", []), ("one hypothesis", ["--hypotheses", "1"])]
    cpu = {name: [] for name, _ in variants}
    for r in range(rounds):
        for x, y in pairs:
            order = variants if r % 2 == 0 else variants[::-1]
            for name, extra in order:
                cpu[name].append(cpu_of([binary, "match", x, y, "-o", out] + extra, env))
    med = {name: statistics.median(v) for name, v in cpu.items()}
    for name, _ in variants:
        print("%-24s median CPU %.3f s over %d runs (%d pairs x %d rounds)" % (name, med[name], len(cpu[name]),
                                                                              len(pairs), rounds))
    print("ratio default / one hypothesis: %.2fx" % (med[variants[0][0]] / med[variants[1][0]]))


if __name__ == "__main__":
    main(sys.argv[1:])
