#!/usr/bin/env bash
# The quick validation grid (tools/validate.c): it must run, and what it prints must hold what
# the paper claims where the paper claims it (docs/model.md §8: the asymptotic law within 10 % of
# the series for u/h0 <= 0.04 on these soft surfaces) and stay in range elsewhere.
# Usage: validate_smoke.sh CT_VALIDATE
source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
out=$("$1" --quick) || fail "ct_validate --quick exited $?"
echo "$out" | awk -F, '
    NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    { rows++
      for (i = 1; i <= NF; i++)
          if ($i !~ /^[-+0-9.eE]+$/) { print "FAIL: row " NR " field " i " = " $i; bad = 1 }
      if (!($(col["dP_asym_series_004"]) < 0.10)) { print "FAIL: paper claim < 10 % broken: " $0; bad = 1 }
      for (c in col)
          if (c ~ /^(dP|de)_/ && !($(col[c]) >= 0 && $(col[c]) < 0.5)) { print "FAIL: " c " = " $(col[c]) " out of [0, 0.5)"; bad = 1 }
      if (!($(col["V_star_crit"]) > 0 && $(col["V_star_crit"]) < $(col["V_star_h0"]))) { print "FAIL: V*_c not below V*_h0: " $0; bad = 1 }
    }
    END { if (rows != 2) { print "FAIL: expected 2 surfaces, got " rows; bad = 1 }
          if (!bad) print "ok: 2 surfaces, claims hold"; exit bad }'
