#!/usr/bin/env bash
# Measured surfaces in the CLI (issue 14): the real Dektak profile's e and V* against an
# independent NumPy computation (tests/profile_reference.py), cantact fit's Rq, Rt and l0
# against it, the units from the file's column names or the scene, the compare columns against
# a Cantor run of the fitted parameters, what = bearing and profile, cantact fit of an X3P
# grid, and every class of bad input: one line naming the file's line or X3P entry, exit 2, no
# output file.
# Usage: test_profile_cli.sh CANTACT SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
ct=$1
src=$(cd "$2" && pwd)
py=/usr/bin/python3

dektak=$src/tests/data/dektak-1.csv
speeds="0.003, 0.01, 0.03, 0.1, 0.3, 1, 3"
cat >"$tmp/d.ini" <<INI
[surface]
type = profile
file = $dektak
H = 10
[material]
E = 2e11
sigma_y = 4e8
[impact]
mass = 1e-3
velocity = $speeds
INI

# 1. e and V* against the independent reference, 1e-9 (bisection to double resolution)
expect 0 "dektak run" -- "$ct" run "$tmp/d.ini" -o "$tmp/e.csv"
has err "dektak-1.csv (dektak): 9600 points, levelled (linear)" "summary line"
has err "measured surface, 9600 rods" "rods line"
# the raw heights' peak to valley in the note: the file's Raw Micrometer column by awk
raw=$(awk -F, 'f && NF >= 2 && $2 != "" { z = $2 + 0; if (n++ == 0 || z < lo) lo = z; if (n == 1 || z > hi) hi = z }
    /^Lateral um,Raw Micrometer/ { f = 1 } END { printf "%.4g", (hi - lo) * 1e-6 }' "$dektak")
has err "(raw Rt $raw m)" "the raw heights' peak to valley"
$py "$src/tests/profile_reference.py" "$dektak" 1e-6 10 2e11 4e8 1e-3 ${speeds//,/} >"$tmp/ref.csv" ||
    bad "profile_reference.py failed"
$py - "$tmp/e.csv" "$tmp/ref.csv" <<'PY' && ok || bad "e, V* against the NumPy reference"
import csv, sys
ours = list(csv.DictReader(open(sys.argv[1])))
ref = [r for r in csv.DictReader(l for l in open(sys.argv[2]) if not l.startswith("#"))]
assert len(ours) == len(ref) == 7, (len(ours), len(ref))
worst = 0.0
for o, r in zip(ours, ref):
    for a, b in ((float(o["V_star"]), float(r["V_star"])), (float(o["e"]), float(r["e"]))):
        worst = max(worst, abs(a - b) / abs(b))
print("worst relative difference to the reference: %.3g" % worst)
assert worst < 1e-9, worst
assert any(float(o["e"]) < 0.9 for o in ours) and any(o["elastic"] == "1" for o in ours)
PY

# 2. cantact fit: Rq, Rt, l0 against the reference; every row finite
expect 0 "fit" -- "$ct" fit "$dektak" -o "$tmp/fit.csv"
read -r _ rq rt l0 < <(grep '^#' "$tmp/ref.csv")
for q in "Rq_m $rq" "Rt_m $rt" "l0_m $l0"; do
    set -- $q
    awk -F, -v k="$1" -v r="$2" '$1 == k { found = 1; d = ($2 - r) / r; if (d < 0) d = -d; if (d > 1e-9) exit 1 }
        END { if (!found) exit 1 }' "$tmp/fit.csv" && ok || bad "fit $1 against the reference $2"
done
for k in alpha h0_m D_variation D_structure D_spectrum D fx fz; do
    awk -F, -v k="$k" '$1 == k { found = 1; if (!($2 + 0 == $2 + 0 && $2 != "nan" && $2 != "inf")) exit 1 }
        END { if (!found) exit 1 }' "$tmp/fit.csv" && ok || bad "fit row $k"
done
has fit.csv "D (into Eq. 3) from the variation estimate" "fit names its estimator"
# D from another estimator: D and fx, fz follow it
expect 0 "fit --dimension structure" -- "$ct" fit "$dektak" --dimension structure -o "$tmp/fs.csv"
[ "$(awk -F, '$1 == "D" { print $2 }' "$tmp/fs.csv")" = "$(awk -F, '$1 == "D_structure" { print $2 }' "$tmp/fs.csv")" ] &&
    ok || bad "--dimension structure: D = D_structure"
[ "$(awk -F, '$1 == "fx" { print $2 }' "$tmp/fs.csv")" != "$(awk -F, '$1 == "fx" { print $2 }' "$tmp/fit.csv")" ] &&
    ok || bad "--dimension structure changes fx"
# Eq. 3 inverted: ln fz = ln 2 (2 - D) / (1 + alpha (D - 1)), fx = fz^alpha
awk -F, '{ v[$1] = $2 } END { a = v["alpha"]; D = v["D"]; lz = log(2) * (2 - D) / (1 + a * (D - 1));
    if ((v["fz"] - exp(lz)) / exp(lz) > 1e-12 || (exp(lz) - v["fz"]) / exp(lz) > 1e-12) exit 1;
    if ((v["fx"] - exp(a * lz)) / v["fx"] > 1e-12 || (exp(a * lz) - v["fx"]) / v["fx"] > 1e-12) exit 1 }' \
    "$tmp/fit.csv" && ok || bad "fx, fz from alpha and D by Eq. 3"
# a scene gives the same fit
expect 0 "fit of a scene" -- "$ct" fit "$tmp/d.ini" -o "$tmp/fit2.csv"
cmp -s <(grep -v '^#' "$tmp/fit.csv") <(grep -v '^#' "$tmp/fit2.csv") && ok || bad "fit of the scene as of the file"

# 3. units: the same profile in nm (column names say so), in a file without names (unit key)
awk -F, 'NR > 28 && NF >= 2 { printf "%.6f,%.6f\n", $1 * 1000, $2 * 1000 }' "$dektak" >"$tmp/nm_body.csv"
{ echo "x (nm),z (nm)"; cat "$tmp/nm_body.csv"; } >"$tmp/nm.csv"
expect 0 "nm profile" -- "$ct" run -q "$tmp/d.ini" --set surface.file="$tmp/nm.csv" -o "$tmp/e_nm.csv"
expect 0 "unitless profile with unit = nm" -- "$ct" run -q "$tmp/d.ini" --set surface.file="$tmp/nm_body.csv" \
    --set surface.unit=nm -o "$tmp/e_nm2.csv"
$py - "$tmp/e.csv" "$tmp/e_nm.csv" "$tmp/e_nm2.csv" <<'PY' && ok || bad "e in nm as in um"
import csv, sys
a, b, c = (list(csv.DictReader(open(p))) for p in sys.argv[1:])
for r in zip(a, b, c):
    for k in ("V_star", "e"):
        x = [float(s[k]) for s in r]
        assert abs(x[1] - x[0]) <= 1e-12 * abs(x[0]) and x[1] == x[2], (k, x)
PY
expect 2 "no unit anywhere" -- "$ct" run "$tmp/d.ini" --set surface.file="$tmp/nm_body.csv" -o "$tmp/none.csv"
has err "nm_body.csv: the length unit of x and z is not given and its column names state none" "no unit"
[ -e "$tmp/none.csv" ] && bad "no unit: a file was left" || ok
# the message names the key that gives the unit (a scene) or the option (cantact fit PROFILE)
has err "state none: give surface.unit (m, mm, um or nm; or surface.x_unit and surface.z_unit)$" \
    "no unit: the key named"
expect 2 "fit: no unit anywhere" -- "$ct" fit "$tmp/nm_body.csv"
has err "state none: give --unit (m, mm, um or nm; or --x-unit and --z-unit)$" "fit, no unit: the option named"
# the micro sign (and the Greek mu) as u: um typed as it is printed
expect 0 "unit = µm" -- "$ct" run -q "$tmp/d.ini" --set surface.file="$tmp/nm_body.csv" \
    --set "surface.unit=µm" -o "$tmp/e_micro.csv"
expect 0 "unit = um" -- "$ct" run -q "$tmp/d.ini" --set surface.file="$tmp/nm_body.csv" \
    --set surface.unit=um -o "$tmp/e_u.csv"
cmp -s "$tmp/e_micro.csv" "$tmp/e_u.csv" && ok || bad "unit = µm is not um"
expect 0 "fit --unit μm (Greek mu)" -- "$ct" fit "$tmp/nm_body.csv" --unit "μm" -o "$tmp/f_mu.csv"
expect 0 "fit --unit um" -- "$ct" fit "$tmp/nm_body.csv" --unit um -o "$tmp/f_u.csv"
cmp -s "$tmp/f_mu.csv" "$tmp/f_u.csv" && ok || bad "fit --unit μm is not um"
expect 2 "unit = µx" -- "$ct" run -q "$tmp/d.ini" --set "surface.unit=µx"
# Hstar in the file's unit: 10 Rt given in um as in nm gives the same e
rt_um=$(awk -v r="$rt" 'BEGIN { printf "%.17g", 10 * r * 1e6 }')
rt_nm=$(awk -v r="$rt" 'BEGIN { printf "%.17g", 10 * r * 1e9 }')
sed 's/^H = 10$/Hstar = '"$rt_um"'/' "$tmp/d.ini" >"$tmp/hs.ini"
"$ct" run -q "$tmp/hs.ini" -o "$tmp/h_um.csv" || bad "Hstar in um"
sed 's/^H = 10$/Hstar = '"$rt_nm"'/' "$tmp/d.ini" >"$tmp/hs.ini"
"$ct" run -q "$tmp/hs.ini" --set surface.file="$tmp/nm.csv" -o "$tmp/h_nm.csv" || bad "Hstar in nm"
$py - "$tmp/e.csv" "$tmp/h_um.csv" "$tmp/h_nm.csv" <<'PY' && ok || bad "Hstar in um and nm as H = 10"
import csv, sys
a, b, c = (list(csv.DictReader(open(p))) for p in sys.argv[1:])
assert len(a) == len(b) == len(c) == 7
for r in zip(a, b, c):
    x = [float(s["e"]) for s in r]
    assert max(x) - min(x) <= 1e-12, x
PY

# 4. compare: the fitted Cantor surface's e is a Cantor run of the fitted parameters
expect 0 "compare" -- "$ct" run -q "$tmp/d.ini" --set output.what=e,compare,bearing,profile \
    -o "$tmp/c.csv"
has c.csv "e_cantor_fit,e_asymptotic_fit,V_star_cantor_fit" "compare columns"
has c_bearing.csv "^d_m,d_over_Rt,phi,phi_fit$" "bearing header"
has c_bearing.csv "^# bearing fit: phi = (d / h0)^alpha" "bearing fit line"
awk -F, '/^[0-9]/ { if (n && ($1 < p || $3 < q)) exit 1; p = $1; q = $3; n++; last = $3 }
    END { if (n < 10 || last != 1) exit 1 }' "$tmp/c_bearing.csv" && ok || bad "bearing: d, phi ascending to phi = 1"
[ "$(grep -c '^[-0-9]' "$tmp/c_profile.csv")" -eq 9600 ] && ok || bad "levelled profile: 9600 rows"
# the run fits on the depths its impacts reach, and says so
has c_bearing.csv "(the depths the impacts reach;" "bearing band from the impacts"
"$ct" run "$tmp/d.ini" --set output.what=compare -o "$tmp/c2.csv" 2>&1 |
    grep -q "^cantact: fit on the depths the impacts reach" && ok || bad "stderr names the band"
# ... from the shallowest reach (not above the 20th highest point) to the deepest u_max
umax=$(awk -F, 'NR > 1 && $3 > m { m = $3 } END { printf "%.17g", m }' "$tmp/c.csv")
awk -v u="$umax" -v rt="$rt" '/^# bearing fit/ { match($0, /on d in \[[^]]*\]/); split(substr($0, RSTART + 9, RLENGTH - 10), b, ", ");
    hi = b[2] + 0; want = u * rt; if (want > rt) want = rt; if (hi > want * (1 + 1e-3) || hi < want * 0.9) exit 1; found = 1 }
    END { if (!found) exit 1 }' "$tmp/c_bearing.csv" && ok || bad "bearing band ends at the deepest u_max"
# ... and from no shallower than the default band's start (the 20th highest point: above it a
# few samples decide alpha; the band is printed to 4 digits), though the slowest impact here
# stops above it
lo_default=$(awk -F, '$1 == "alpha" { print $3 }' "$tmp/fit.csv")
awk -F, -v rt="$rt" -v lo="$lo_default" 'NR > 1 && (m == "" || $3 < m) { m = $3 }
    END { if (!(m * rt < lo)) exit 1 }' "$tmp/c.csv" && ok || bad "the slowest impact stops above the default band"
awk -v lo="$lo_default" '/^# bearing fit/ { match($0, /on d in \[[^]]*\]/); split(substr($0, RSTART + 9, RLENGTH - 10), b, ", ");
    if (b[1] + 0 < lo * (1 - 1e-3)) exit 1; found = 1 } END { if (!found) exit 1 }' "$tmp/c_bearing.csv" &&
    ok || bad "bearing band starts no shallower than the default band"
# the fitted parameters of the run (its bearing file), then a Cantor run of them gives e_cantor_fit
cf() { sed -n "s/^# Cantor fit.* $1 = \([^ ,]*\).*/\1/p" "$tmp/c_bearing.csv"; }
fx=$(cf fx)
fz=$(cf fz)
h0=$(cf h0)
vc=$(awk -F, 'NR > 1 { printf "%s%s", (NR > 2 ? ", " : ""), $12 }' "$tmp/c.csv")
cat >"$tmp/cantor.ini" <<INI
[surface]
fx = $fx
fz = $fz
depth = fractal
H = $(awk -v r="$rt" -v h="$h0" 'BEGIN { printf "%.17g", 10 * r / h }')
[material]
E = 500
[impact]
V_star = $vc
INI
if "$ct" run -q "$tmp/cantor.ini" -o "$tmp/cantor.csv" 2>"$tmp/cantor.err"; then
    $py - "$tmp/c.csv" "$tmp/cantor.csv" <<'PY' && ok || bad "e_cantor_fit against a Cantor run of the fit"
import csv, sys
a, b = (list(csv.DictReader(open(p))) for p in sys.argv[1:])
assert len(a) == len(b) == 7
for r, s in zip(a, b):
    assert abs(float(r["e_cantor_fit"]) - float(s["e"])) <= 1e-12, (r["e_cantor_fit"], s["e"])
PY
else
    bad "the Cantor run of the fitted parameters: $(cat "$tmp/cantor.err")"
fi

# 5. an X3P grid (written here, Python's zipfile): each valid pixel a rod, the mask counted
$py - "$tmp" <<'PY' || bad "writing X3P files"
import math, struct, sys, zipfile
d = sys.argv[1]
def x3p(name, nx, ny, z, size=None, main=True, mask=None):
    xml = ('<?xml version="1.0" encoding="UTF-8"?>\n<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2">'
           '<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType><Axes>'
           '<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment><Offset>0</Offset></CX>'
           '<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment><Offset>0</Offset></CY>'
           '<CZ><AxisType>A</AxisType><DataType>D</DataType><Increment>1</Increment><Offset>0</Offset></CZ>'
           '</Axes></Record1><Record3><MatrixDimension><SizeX>%d</SizeX><SizeY>%d</SizeY><SizeZ>1</SizeZ>'
           '</MatrixDimension><DataLink><PointDataLink>bindata/data.bin</PointDataLink>%s</DataLink></Record3>'
           '</p:ISO5436_2>' % (size or nx, ny, '<ValidPointsLink>bindata/valid.bin</ValidPointsLink>' if mask else ''))
    with zipfile.ZipFile("%s/%s" % (d, name), "w") as f:
        if main:
            f.writestr("main.xml", xml)
        f.writestr("bindata/data.bin", struct.pack("<%dd" % len(z), *z))
        if mask:
            f.writestr("bindata/valid.bin", bytes(mask))
n = 64
z = [1e-7 * (math.sin(0.3 * i) * math.cos(0.21 * j) + math.sin(1.7 * i + 2.3 * j)) for j in range(n) for i in range(n)]
x3p("g.x3p", n, n, z, mask=[0xfe] + [0xff] * (n * n // 8 - 1))  # point 0 invalid
x3p("nomain.x3p", n, n, z, main=False)
x3p("size.x3p", n, n, z, size=n + 1)
x3p("flat.x3p", n, n, [0.0] * (n * n))
PY
cat >"$tmp/g.ini" <<INI
[surface]
type = profile
file = g.x3p
H = 5
[material]
E = 2e11
sigma_y = 4e8
[impact]
mass = 1e-9
velocity = 0.01, 0.1, 1
INI
expect 0 "x3p run" -- "$ct" run "$tmp/g.ini" -o "$tmp/g.csv"
has err "g.x3p (x3p): 4095 points on a grid" "x3p summary"
has err "4.095e-09 m^2" "x3p area"
has err "1 invalid points left out" "x3p mask"
[ "$(grep -c '^1,' "$tmp/g.csv")" -eq 3 ] && ok || bad "x3p: 3 rows"
# the fitted Cantor surface of a grid gets the energy per unit depth of the grid's extent:
# V*_fit = sqrt(m v^2 / 2 / (l0 E h0_fit) / depth), l0 = depth = 64 um, from the scene's m, v, E
expect 0 "x3p compare" -- "$ct" run -q "$tmp/g.ini" --set output.what=e,compare,bearing -o "$tmp/gc.csv"
h0g=$(sed -n "s/^# Cantor fit.* h0 = \([^ ,]*\).*/\1/p" "$tmp/gc_bearing.csv")
$py - "$tmp/gc.csv" "$h0g" <<'PY' && ok || bad "x3p: V*_fit from the energy per unit depth"
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
h0 = float(sys.argv[2])
assert [float(r["V_star"]) > 0 for r in rows] == [True] * 3
for r, v in zip(rows, (0.01, 0.1, 1.0)):
    want = math.sqrt(1e-9 * v * v / 2 / (64e-6 * 2e11 * h0) / 64e-6)
    got = float(r["V_star_cantor_fit"])
    assert abs(got - want) <= 1e-12 * want, (got, want)
PY
expect 0 "x3p fit" -- "$ct" fit "$tmp/g.x3p" -o "$tmp/gfit.csv"
has gfit.csv "^# x3p: 4095 points" "x3p fit header"
OMP_NUM_THREADS=1 "$ct" run -q "$tmp/g.ini" -o "$tmp/g1.csv"
OMP_NUM_THREADS=2 "$ct" run -q "$tmp/g.ini" --set solver.threads=2 -o "$tmp/g2.csv"
cmp -s "$tmp/g1.csv" "$tmp/g2.csv" && ok || bad "x3p: 1 and 2 threads differ"

# 6. bad input: one line, exit 2, no output file
printf 'x um,z um\n0,1\n1,2\n2,abc\n3,4\n' >"$tmp/nonnum.csv"
printf 'x um,z um\n0,1\n1,2\n1,3\n' >"$tmp/xdec.csv"
printf 'x um,z um\n0,1\n1,2\n' >"$tmp/two.csv"
printf 'x um,z um\n0,1\n1,1\n2,1\n3,1\n' >"$tmp/flat.csv"
# each line: a sed expression on the scene | --set options | the message
while IFS='|' read -r edit sets message; do
    sed "$edit" "$tmp/d.ini" >"$tmp/bad.ini"
    # shellcheck disable=SC2086
    expect 2 "bad: $edit $sets" -- "$ct" run "$tmp/bad.ini" $sets -o "$tmp/none.csv"
    has err "$message" "bad: $edit $sets"
    [ -e "$tmp/none.csv" ] && bad "bad: $edit $sets: a file was left" || ok
done <<BAD
s/x/x/|--set surface.file=$tmp/nonnum.csv|nonnum.csv:4: not a row of numbers
s/x/x/|--set surface.file=$tmp/xdec.csv|xdec.csv:4: x = 1e-06 is not above the previous 1e-06
s/x/x/|--set surface.file=$tmp/two.csv|two.csv: 2 points: a profile needs at least 3
s/x/x/|--set surface.file=$tmp/nomain.x3p|nomain.x3p: X3P entry main.xml missing
s/x/x/|--set surface.file=$tmp/size.x3p|bindata/data.bin holds 32768 bytes
s/x/x/|--set surface.file=$tmp/flat.csv|all heights are equal after levelling
s/x/x/|--set surface.file=$tmp/missing.csv|missing.csv: cannot open
s/x/x/|--set surface.file=$tmp/g.x3p --set surface.unit=um|an X3P file states its lengths
s/^H = 10$/Hstar = 0.1/||must exceed the profile's peak-to-valley depth
s/^H = 10$/H = 10\nHstar = 5/||needs one of surface.H
s/x/x/|--set surface.H=1|must satisfy H > 1
s/x/x/|--set surface.unit=furlong|surface.unit = furlong: must be m, mm, um or nm
s/x/x/|--set surface.fx=1.5|surface.fx = 1.5: only for surface.type = cantor or random_cantor (not profile)
s/x/x/|--set fit.dimension=fourier|fit.dimension = fourier: must be variation, structure or spectrum
s/x/x/|--set surface.detrend=cubic|must be none, mean, linear or quadratic
s/x/x/|--set surface.trim=iso|must be none or rq
/^sigma_y/d||material.sigma_y: required key missing
/^file/d||surface.file: required key missing
s/x/x/|--set impact.mass=0|impact.mass
BAD
expect 2 "fit of a flat profile" -- "$ct" fit "$tmp/flat.csv" -o "$tmp/none.csv"
has err "all heights are equal" "fit of a flat profile"
[ -e "$tmp/none.csv" ] && bad "fit of a flat profile: a file was left" || ok
# a zip whose main.xml states 2.7 GB (found by the fuzzer): refused before any allocation
expect 2 "forged zip entry size" -- "$ct" fit "$src/tests/fuzz_corpus_profile/forged_size.x3p"
has err "X3P entry main.xml holds 2667577856 bytes: more than the 67108864 it may hold" "forged size named"
expect 2 "fit of a flat grid" -- "$ct" fit "$tmp/flat.x3p"
expect 2 "profile keys with a Cantor surface" -- "$ct" run "$tmp/cantor.ini" --set surface.detrend=mean
has err "surface.detrend = mean: only for surface.type = profile" "profile key with cantor"
expect 2 "fit keys with a Cantor surface" -- "$ct" run "$tmp/cantor.ini" --set fit.lag_lo=1
expect 2 "fit: unknown option" -- "$ct" fit "$dektak" --frob
# a dimension outside (1, 2) is flagged, in the table and on stderr (even under -q): white noise
# has a flat spectrum, C(q) ~ q^0, so D_spectrum = 5/2; the Dektak profile's three lie inside
awk 'BEGIN { x = 12345; print "x (um),z (um)"
    for (i = 0; i < 4000; i++) { s = 0; for (k = 0; k < 12; k++) { x = (x * 1103515245 + 12345) % 2147483648; s += x / 2147483648 }
        printf "%d,%.9f\n", i, (s - 6) * 0.1 } }' >"$tmp/white.csv"
expect 0 "fit of white noise" -- "$ct" fit -q "$tmp/white.csv" -o "$tmp/white_fit.csv"
ds=$(awk -F, '$1 == "D_spectrum" { print $2 }' "$tmp/white_fit.csv")
awk -v d="$ds" 'BEGIN { exit !(d > 2.3 && d < 2.7) }' && ok || bad "white noise: D_spectrum = $ds, not about 5/2"
grep -q "^# warning: .*D_spectrum = .* outside (1, 2), the range of a fractal profile's dimension" "$tmp/white_fit.csv" &&
    ok || bad "white noise: no warning in the table: $(head -3 "$tmp/white_fit.csv")"
[ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q "^cantact: warning: .*D_spectrum = .* outside (1, 2)" "$tmp/err" && ok ||
    bad "white noise: no warning on stderr: $(cat "$tmp/err")"
grep -q "describe no Cantor surface" "$tmp/err" && bad "white noise: D from the variation flagged" || ok
expect 0 "fit of white noise, D from the spectrum" -- "$ct" fit "$tmp/white.csv" --dimension spectrum -o "$tmp/white_fit2.csv"
has err "D, fx and fz come from D_spectrum, so they describe no Cantor surface" "white noise: fx, fz flagged"
expect 0 "fit of the Dektak profile: no warning" -- "$ct" fit "$dektak" -o "$tmp/dk_fit.csv"
[ ! -s "$tmp/err" ] && ! grep -q "warning" "$tmp/dk_fit.csv" && ok || bad "Dektak: a warning: $(cat "$tmp/err")"
awk -F, '$1 ~ /^D/ && !($2 > 1 && $2 < 2) { exit 1 }' "$tmp/dk_fit.csv" && ok || bad "Dektak: a D outside (1, 2) unflagged"
# scripts/measured takes a scene (any measured surface's) and -o OUTDIR, and --help is its own
command -v gnuplot >/dev/null || fail "gnuplot (scripts' package gnuplot-nox) is needed for scripts/measured"
expect 0 "scripts/measured --help" -- env CT_CANTACT="$ct" "$src/scripts/measured" --help
has out "^Usage: scripts/measured \[SCENE.ini\] \[-o OUTDIR\]" "scripts/measured --help: its own usage"
CT_CANTACT="$ct" "$src/scripts/measured" "$tmp/d.ini" -o "$tmp/meas" --set impact.velocity=0.001:3:6:log \
    >"$tmp/out" 2>"$tmp/err" && ok || bad "scripts/measured SCENE.ini: $(cat "$tmp/err")"
for f in measured.csv measured_fit.csv measured_bearing.csv measured_e.png measured_bearing.png; do
    [ -s "$tmp/meas/$f" ] && ok || bad "scripts/measured SCENE.ini: no $f"
done
[ "$(grep -c '^[0-9]' "$tmp/meas/measured.csv")" -eq 6 ] && ok || bad "scripts/measured: not the scene's run at 6 speeds"
cmp -s <(grep -v '^#' "$tmp/meas/measured_fit.csv") <(grep -v '^#' "$tmp/fit2.csv") && ok ||
    bad "scripts/measured: its fit is not cantact fit's of the scene"
expect 2 "scripts/measured OUTDIR (not a scene)" -- env CT_CANTACT="$ct" "$src/scripts/measured" "$tmp/meas"
has err "not a scene (SCENE.ini; the output directory is -o OUTDIR)" "scripts/measured OUTDIR"
expect 2 "scripts/measured of a Cantor scene" -- env CT_CANTACT="$ct" "$src/scripts/measured" "$tmp/cantor.ini" -o "$tmp/meas2"
has err "a bearing-area curve is written for measured surfaces" "scripts/measured of a Cantor scene"
expect 2 "fit: bad unit" -- "$ct" fit "$dektak" --unit furlong
expect 2 "fit: bad band" -- "$ct" fit "$dektak" --lags 3:1
expect 2 "fit: scene and file options" -- "$ct" fit "$tmp/d.ini" --unit um
expect 2 "fit: a Cantor scene" -- "$ct" fit "$tmp/cantor.ini"
expect 0 "fit --help" -- "$ct" fit --help
has out "Usage: cantact fit PROFILE" "fit --help"
has out "--dimension M" "fit --help lists --dimension"
expect 0 "run --help" -- "$ct" run --help
has out "  profile: file unit x_unit z_unit" "run --help: profile keys"
has out "bearing:" "run --help: bearing output"

finish
