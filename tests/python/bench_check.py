"""Checks of `specseg eval --benchmark` outputs for tests/cli_eval_benchmark*.sh (stdlib only).

usage: bench_check.py OUTDIR RECOMPUTED EXPECT
  OUTDIR      the run's folder (pairs.csv, summary.json)
  RECOMPUTED  one line per scored (method, x, y): "method x y K KS E1 E2 JSON" with E1 the per-point
              errors `specseg error MAPK Y --gt GTK -o E1` wrote (K lines), E2 the same against the
              mirror points (KS lines; "-" when Y has none) and JSON its --json output
  EXPECT      "method:pairs:scored:skipped,..." the counts the run must report
Every number of summary.json is recomputed from these (means, medians, % above 5, symmetric means,
the curve, per class) and from pairs.csv for what only the run knows (seconds, confidence); pairs.csv's
scored rows must equal the recomputation to 1e-9. Prints "N checks" or the failures (exit 1).
"""
import csv
import json
import math
import sys

TOL = 1e-9
fails = []
nchecks = 0


def check(cond, what):
    global nchecks
    nchecks += 1
    if not cond:
        fails.append(what)


def near(a, b, what, tol=TOL):
    if a is None or b is None:
        check(a is None and b is None, "%s: %r vs %r" % (what, a, b))
    else:
        check(abs(a - b) <= tol * max(1.0, abs(b)), "%s: %.17g vs %.17g" % (what, a, b))


def pair_class(x, y):
    def cls(n):
        k = len(n)
        while k > 0 and n[k - 1].isdigit():
            k -= 1
        return n[:k] if k else n
    a, b = cls(x), cls(y)
    return a if a == b else a + "/" + b


def median(v):
    v = sorted(v)
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


outdir, recfile, expect = sys.argv[1], sys.argv[2], sys.argv[3]
# pairs.csv, one row per key (a scored row wins, else the last)
rows = {}
with open(outdir + "/pairs.csv", newline="") as f:
    for r in csv.DictReader(f):
        key = (r["method"], r["x"], r["y"])
        if key in rows and rows[key]["status"] == "ok":
            continue
        rows[key] = r
# the recomputation
rec = {}
for line in open(recfile):
    m, x, y, K, KS, e1, e2, js = line.split()
    err = [float(t) for t in open(e1).read().split()]
    K, KS = int(K), int(KS)
    check(len(err) == K, "%s %s %s: %d errors, K = %d" % (m, x, y, len(err), K))
    res = json.load(open(js))["results"][0]
    sym = None
    if e2 != "-":
        err2 = [float(t) for t in open(e2).read().split()]
        s = 0.0
        for k in range(KS):
            s += min(err[k], err2[k])
        sym = s / KS
    rec[(m, x, y)] = dict(K=K, KS=KS, err=err, mean=res["mean_error"], median=res["median_error"], sym=sym)
# pairs.csv against the recomputation
grid = [0.25 * j / 250 for j in range(251)]
for key, r in rows.items():
    if r["status"] != "ok":
        check(key not in rec, "%s: skipped in pairs.csv but recomputed" % (key,))
        continue
    check(key in rec, "%s: scored in pairs.csv, not recomputed" % (key,))
    if key not in rec:
        continue
    c = rec[key]
    near(float(r["mean"]), c["mean"], "%s mean" % (key,))
    near(float(r["median"]), c["median"], "%s median" % (key,))
    near(float(r["sym_mean"]) if r["sym_mean"] else None, c["sym"], "%s symmetric mean" % (key,))
    check(int(r["points"]) == c["K"], "%s points %s vs %d" % (key, r["points"], c["K"]))
    check(int(r["sym_points"]) == (c["KS"] if c["sym"] is not None else 0), "%s sym_points" % (key,))
    cum = [int(t) for t in r["cum"].split()]
    check(cum == [sum(1 for e in c["err"] if e <= t) for t in grid], "%s cumulative counts" % (key,))
# summary.json against the recomputation
S = json.load(open(outdir + "/summary.json"))
want = {}
for item in expect.split(","):
    m, p, s, k = item.split(":")
    want[m] = (int(p), int(s), int(k))
check(sorted(M["method"] for M in S["methods"]) == sorted(want), "methods %r vs %r" % ([M["method"] for M in S["methods"]], sorted(want)))


def stats(keys, M, what):
    sc = [k for k in keys if rows[k]["status"] == "ok"]
    check(M["pairs"] == len(keys), "%s pairs %d vs %d" % (what, M["pairs"], len(keys)))
    check(M["scored"] == len(sc), "%s scored %d vs %d" % (what, M["scored"], len(sc)))
    check(M["skipped"] == len(keys) - len(sc), "%s skipped" % what)
    means = [rec[k]["mean"] for k in sc]
    if means:
        near(M["mean_x100"], 100 * (sum(means) / len(means)), what + " mean_x100")
        near(M["median_x100"], 100 * median(means), what + " median_x100")
        near(M["above5_percent"], 100.0 * sum(1 for v in means if 100 * v > 5) / len(means), what + " above5_percent")
    else:
        check(M["mean_x100"] is None and M["median_x100"] is None and M["above5_percent"] is None, what + " nulls")
    sy = [rec[k]["sym"] for k in sc if rec[k]["sym"] is not None]
    check(M["sym_pairs"] == len(sy), "%s sym_pairs %d vs %d" % (what, M["sym_pairs"], len(sy)))
    near(M["sym_mean_x100"], 100 * (sum(sy) / len(sy)) if sy else None, what + " sym_mean_x100")
    secs = [float(rows[k]["seconds"]) for k in sc if rows[k]["seconds"]]
    check(M["timed"] == len(secs), "%s timed" % what)
    near(M["seconds_mean"], sum(secs) / len(secs) if secs else None, what + " seconds_mean", 1e-12)
    check(M["not_confident"] == sum(1 for k in sc if rows[k]["confident"] == "0"), what + " not_confident")
    return sc


for M in S["methods"]:
    m = M["method"]
    keys = sorted(k for k in rows if k[0] == m)
    if m in want:
        check((M["pairs"], M["scored"], M["skipped"]) == want[m],
              "%s: pairs/scored/skipped %d/%d/%d, expected %d/%d/%d" % ((m, M["pairs"], M["scored"], M["skipped"]) + want[m]))
    sc = stats(keys, M, m)
    pts = sum(rec[k]["K"] for k in sc)
    check(M["points"] == pts, "%s points %d vs %d" % (m, M["points"], pts))
    allerr = [e for k in sc for e in rec[k]["err"]]
    check(len(M["curve"]["error"]) == 251 and len(M["curve"]["fraction"]) == 251, m + " curve length")
    for j, t in enumerate(grid):
        near(M["curve"]["error"][j], t, "%s curve error %d" % (m, j), 1e-15)
        near(M["curve"]["fraction"][j], sum(1 for e in allerr if e <= t) / len(allerr) if allerr else None,
             "%s curve fraction %d" % (m, j), 1e-15)
    classes = sorted(set(pair_class(k[1], k[2]) for k in keys))
    check([c["class"] for c in M["classes"]] == classes, "%s classes %r vs %r" % (m, [c["class"] for c in M["classes"]], classes))
    for C in M["classes"]:
        stats([k for k in keys if pair_class(k[1], k[2]) == C["class"]], C, "%s class %s" % (m, C["class"]))
if fails:
    for f in fails:
        print("FAIL:", f)
    sys.exit(1)
print("%d checks" % nchecks)
