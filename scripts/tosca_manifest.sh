#!/usr/bin/env bash
# Writes a `specseg eval --manifest` file for the TOSCA classes under DATA_DIR/tosca (nothing is
# copied: the manifest names the data's own files, by absolute path).
#   scripts/tosca_manifest.sh DATA_DIR [--split tune|held|all] [--max N] [CLASS...] > tosca.manifest
# One group per class (cat centaur david dog horse michael victoria wolf unless CLASS... given),
# ground truth = identity (every file of a class has the same connectivity and vertex order), GT
# landmarks = the paper's FPS procedure on the class's first shape (lowest number, e.g. cat0, seeded
# at its vertex 0) carried to the others by the identity. Pairs (shapes in numeric order s0 s1 ...):
#   tune  s0 -> s1, s0 -> s2, ... (the reference against the others; at most --max per class)
#   held  s1 -> s2, s2 -> s1, s2 -> s3, s3 -> s2, ... (pairs without the reference, disjoint from
#         the tune pairs; at most --max per class)
#   all   every ordered pair of the class
# --max defaults to 6.
set -eu
usage() { sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
[ $# -ge 1 ] || usage
DATA=$1; shift
SPLIT=tune; MAX=6; CLASSES=()
while [ $# -gt 0 ]; do
  case $1 in
    --split) SPLIT=${2:?}; shift 2 ;;
    --max) MAX=${2:?}; shift 2 ;;
    -h|--help) usage ;;
    -*) echo "tosca_manifest.sh: unknown option $1" >&2; exit 2 ;;
    *) CLASSES+=("$1"); shift ;;
  esac
done
case $SPLIT in tune|held|all) ;; *) echo "tosca_manifest.sh: --split tune, held or all" >&2; exit 2 ;; esac
[ ${#CLASSES[@]} -gt 0 ] || CLASSES=(cat centaur david dog horse michael victoria wolf)
DIR=$(cd "$DATA/tosca" 2> /dev/null && pwd) || { echo "tosca_manifest.sh: no folder $DATA/tosca" >&2; exit 1; }
echo "specseg-manifest 1"
echo "# TOSCA classes from $DIR, split $SPLIT (scripts/tosca_manifest.sh)"
for c in "${CLASSES[@]}"; do
  mapfile -t S < <(cd "$DIR" && ls "$c"[0-9]*.off 2> /dev/null | sed "s/^$c\([0-9]*\)\.off$/\1/" | sort -n)
  [ ${#S[@]} -ge 2 ] || { echo "tosca_manifest.sh: class $c: fewer than two shapes in $DIR" >&2; exit 1; }
  echo
  echo "group $c"
  echo "gt identity"
  echo "landmarks fps $c${S[0]}"
  for i in "${S[@]}"; do echo "mesh $DIR/$c$i.off"; done
  case $SPLIT in
    all) echo "pairs all" ;;
    tune)
      echo "pairs listed"
      n=0
      for ((j = 1; j < ${#S[@]} && n < MAX; j++)); do echo "pair $c${S[0]} $c${S[j]}"; n=$((n + 1)); done ;;
    held)
      echo "pairs listed"
      n=0
      for ((j = 1; j + 1 < ${#S[@]} && n < MAX; j++)); do
        echo "pair $c${S[j]} $c${S[j + 1]}"; n=$((n + 1))
        [ $n -lt "$MAX" ] && { echo "pair $c${S[j + 1]} $c${S[j]}"; n=$((n + 1)); }
      done
      [ $n -gt 0 ] || { echo "tosca_manifest.sh: class $c: no held-out pair (3 shapes needed)" >&2; exit 1; } ;;
  esac
done
