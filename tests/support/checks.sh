# What the shell tests share (source it): failures counted rather than
# fatal, a command run with its output and status kept, the two answers
# every command line owes (--help, and a misspelling refused with exit 2
# and the nearest name), and the closing verdict.

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Runs COMMAND... with no input, 20 s at most; sets $out (stdout and
# stderr) and $status.
run() {
  out=$(timeout 20 "$@" 2>&1 </dev/null)
  status=$?
}

# expect_help LABEL HELP_LINE COMMAND...: exits 0 and prints HELP_LINE.
expect_help() {
  local label=$1 help_line=$2
  shift 2
  run "$@"
  [[ $status -eq 0 ]] || fail "$label --help exited $status: $out"
  [[ $out == *"$help_line"* ]] || fail "$label --help does not say '$help_line': $out"
}

# expect_misspelling LABEL SUGGESTION COMMAND...: exits 2 and asks "did
# you mean 'SUGGESTION'?".
expect_misspelling() {
  local label=$1 suggestion=$2
  shift 2
  run "$@"
  [[ $status -eq 2 ]] || fail "$label exited $status (want 2): $out"
  [[ $out == *"did you mean '$suggestion'?"* ]] || fail "$label: no did-you-mean '$suggestion': $out"
}

# The last line: how many checks failed (exit 1), or SUCCESS_LINE.
finish() {
  if ((failures > 0)); then
    echo "$failures failure(s)"
    exit 1
  fi
  echo "$*"
}
