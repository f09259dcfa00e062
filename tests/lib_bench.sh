# Sourced by the benchmark tests (after lib_cli.sh): the independent recomputation of a scored pair
# with `specseg error` on the K points both .vts files have (K = the shorter file), and of its
# symmetric error on the .sym.vts points. Needs BIN, TMP and REC (the file the records go to, one
# line "METHOD X Y K KS ERR_FILE SYM_ERR_FILE|- JSON" a pair, read by tests/python/bench_check.py).
recompute() { # METHOD X Y MAP FOLDER (the meshes and their corres/)
  local m=$1 x=$2 y=$3 map=$4 S=$5 d=$TMP/rec/$1.$2.$3
  local vx=$S/corres/$x.vts vy=$S/corres/$y.vts sy=$S/corres/$y.sym.vts
  local nx ny K KS=0 e2=-
  mkdir -p "$TMP/rec"
  nx=$(wc -l < "$vx") ny=$(wc -l < "$vy")
  K=$((nx < ny ? nx : ny))
  head -n "$K" "$vx" | awk 'NR == FNR { m[NR - 1] = $1; next } { print m[$1 - 1] }' "$map" - > "$d.mk"
  head -n "$K" "$vy" | awk '{ print $1 - 1 }' > "$d.gk"
  "$BIN" error "$d.mk" "$S/$y.off" --gt "$d.gk" -o "$d.e1" --json > "$d.json" || bad "specseg error $m $x $y"
  if [ -f "$sy" ]; then
    KS=$(wc -l < "$sy")
    KS=$((KS < K ? KS : K))
    head -n "$KS" "$sy" | awk '{ print $1 - 1 }' > "$d.sk"
    head -n "$KS" "$d.mk" > "$d.mks"
    "$BIN" error "$d.mks" "$S/$y.off" --gt "$d.sk" -o "$d.e2" > /dev/null || bad "specseg error --sym $m $x $y"
    e2=$d.e2
  fi
  echo "$m $x $y $K $KS $d.e1 $e2 $d.json" >> "$REC"
}
