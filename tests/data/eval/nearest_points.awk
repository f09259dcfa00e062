# Ground-truth points of a remeshed shape, as the remeshed benchmarks made theirs: for K points of the
# original mesh (its vertices (k * 113) mod n, k < K; first file), the 1-based index of the nearest
# vertex of the remeshed mesh (second file). Both files OFF with one vertex a line.
# usage: awk -v K=60 -f nearest_points.awk ORIGINAL.off REMESHED.off > NAME.vts
FNR == 1 { f++ }
FNR == 2 { nv[f] = $1 }
FNR >= 3 && FNR < 3 + nv[f] { x[f, FNR - 3] = $1; y[f, FNR - 3] = $2; z[f, FNR - 3] = $3 }
END {
  for (k = 0; k < K; k++) {
    v = (k * 113) % nv[1]; best = -1
    for (i = 0; i < nv[2]; i++) {
      d = (x[2, i] - x[1, v])^2 + (y[2, i] - y[1, v])^2 + (z[2, i] - z[1, v])^2
      if (best < 0 || d < bd) { bd = d; best = i }
    }
    print best + 1
  }
}
