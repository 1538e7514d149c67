# Shared by the scripts in scripts/: --help from the script's own header
# comment, and unknown options refused with the nearest known one.
# Source it:  source "$(dirname "$0")/lib/cli.sh"

# Prints the header comment of script $1 (the lines after the shebang that
# start with '#', up to the first that does not), without the '# '.
sp_print_help() {
  awk 'NR == 1 && /^#!/ { next } /^#/ { sub(/^# ?/, ""); print; next } { exit }' "$1"
}

# Levenshtein distance of $1 and $2 (short strings: option names).
sp_edit_distance() {
  awk -v a="$1" -v b="$2" 'BEGIN {
    n = length(a); m = length(b)
    for (j = 0; j <= m; j++) d[0, j] = j
    for (i = 1; i <= n; i++) {
      d[i, 0] = i
      for (j = 1; j <= m; j++) {
        cost = (substr(a, i, 1) == substr(b, j, 1)) ? 0 : 1
        v = d[i - 1, j] + 1
        if (d[i, j - 1] + 1 < v) v = d[i, j - 1] + 1
        if (d[i - 1, j - 1] + cost < v) v = d[i - 1, j - 1] + cost
        d[i, j] = v
      }
    }
    print d[n, m]
  }'
}

# sp_unknown PROGRAM WORD KNOWN...: says WORD (an option, or a command when
# it has no leading '-') is unknown, naming the nearest of KNOWN when it is
# close (one edit for a short name, two for one of 4 letters or more; a
# name WORD begins wins a tie), and exits 2.
sp_unknown() {
  local program=$1 word=$2 best="" best_score=1000 candidate distance score limit
  shift 2
  local bare=${word%%=*} what=option
  [[ $bare == -* ]] || what=command
  for candidate in "$@"; do
    distance=$(sp_edit_distance "$bare" "$candidate")
    limit=1
    (( ${#candidate} >= 4 )) && limit=2
    (( distance <= limit )) || continue
    score=$(( distance * 2 ))
    [[ $candidate == "$bare"* ]] && score=$(( score - 1 ))
    if (( score < best_score )); then best=$candidate; best_score=$score; fi
  done
  if [[ -n "$best" ]]; then
    echo "$program: unknown $what '$word' (did you mean '$best'?); see $program --help" >&2
  else
    echo "$program: unknown $what '$word'; see $program --help (it takes: $*)" >&2
  fi
  exit 2
}
