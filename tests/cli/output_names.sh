#!/usr/bin/env bash
# A deck is data: no output directory or case name ever reaches a shell.
# Names with $(...), backticks, quotes, spaces, non-ASCII letters and ../
# create exactly the files expected, and nothing else; a name with a
# control character is refused (exit 1) before anything is written.
#   output_names.sh EXE
source "$(dirname "$0")/common.sh" "$1"
cp "$ROOT/tests/regression/elastic_bar/elastic_bar.msh" "$W/bar.msh"
deck() {   # folder, directory, case name (namelist string bodies, quotes doubled)
  printf '%s\n' "&run t_end = 2e-7 /" "&mesh file = '../bar.msh' /" \
    "&material name = 'steel', rho0 = 7850, youngs_modulus = 200e9, poisson_ratio = 0.3 /" \
    "&part group = 'bar', material = 'steel' /" "&output directory = '$2', case_name = '$3' /" > "$1/deck/case.nml"
}
names=0
# every file below folder, sorted
files() { find "$1" -type f | LC_ALL=C sort; }
expect_files() {   # test name, directory as the deck gives it, as the file system sees it, case name, as seen
  local name=$1 d=$2 dfs=$3 c=$4 cfs=$5 rc want got base
  names=$((names + 1))
  base=$W/case_$names
  mkdir -p "$base/deck"; cp "$W/bar.msh" "$base/"
  deck "$base" "$d" "$c"
  (cd "$base/deck" && "$EXE" case.nml > "$W/log.txt" 2>&1); rc=$?
  got=$(files "$base")
  want=$( { printf '%s\n' "$base/bar.msh" "$base/deck/case.nml"
            for f in "$cfs.h5" "$cfs.xmf" "${cfs}_history.csv" "$cfs.status"; do realpath -m -- "$base/deck/$dfs/$f"; done
          } | LC_ALL=C sort)
  if [ $rc = 0 ] && [ "$got" = "$want" ]; then ok "$name"
  else bad "$name (exit $rc)"; diff <(echo "$want") <(echo "$got"); tail -3 "$W/log.txt"; fi
}
expect_files command_substitution 'out$(touch pwned_1)' 'out$(touch pwned_1)' 'case$(touch pwned_2)' 'case$(touch pwned_2)'
expect_files backticks 'out`touch pwned_3`' 'out`touch pwned_3`' 'c`touch pwned_4`' 'c`touch pwned_4`'
expect_files quotes "it''s \"quoted\"" "it's \"quoted\"" "a \"b\" ''c''" "a \"b\" 'c'"
expect_files spaces_and_dollar 'my out/$HOME x' 'my out/$HOME x' 'run $1 ;ls' 'run $1 ;ls'
expect_files non_ascii 'résultats/удар' 'résultats/удар' 'taylor_δ' 'taylor_δ'
expect_files parent_folder '../up/one' '../up/one' 'case' 'case'
expect_files semicolon_and_pipe 'x; touch pwned_5 | cat' 'x; touch pwned_5 | cat' 'k&&touch pwned_6' 'k&&touch pwned_6'
# a case name is a file name: no folder in it, no escape from the output folder
for c in '../../escaped' 'sub/case' '/tmp/abs' '..'; do
  names=$((names + 1))
  base=$W/case_$names
  mkdir -p "$base/deck"; cp "$W/bar.msh" "$base/"
  deck "$base" "out" "$c"
  (cd "$base/deck" && "$EXE" case.nml > "$W/log.txt" 2>&1); rc=$?
  if [ $rc = 1 ] && [ "$(files "$base" | wc -l)" = 2 ] && grep -q 'case.nml:5: &output: case_name' "$W/log.txt"; then ok "case_name_${c//\//_}_refused"
  else bad "case_name '$c' (exit $rc)"; cat "$W/log.txt"; files "$base"; fi
done
if find "$W" / -maxdepth 1 -name 'pwned*' 2>/dev/null | grep -q . || find "$W" -name 'pwned*' | grep -q .; then
  bad "a command ran: $(find "$W" -name 'pwned*')"; else ok "no_command_ran"; fi
# control characters: refused before anything is written
for cc in $'\t' $'\x01' $'\x1b'; do
  names=$((names + 1))
  base=$W/case_$names
  mkdir -p "$base/deck"; cp "$W/bar.msh" "$base/"
  deck "$base" "out${cc}x" "case"
  (cd "$base/deck" && "$EXE" case.nml > "$W/log.txt" 2>&1); rc=$?
  if [ $rc = 1 ] && [ "$(files "$base" | wc -l)" = 2 ] && grep -qi 'control character' "$W/log.txt"; then ok "control_character_$(printf '%02x' "'$cc")_refused"
  else bad "control character $(printf '%q' "$cc") (exit $rc)"; cat "$W/log.txt"; fi
done
grep -rn 'execute_command_line\|call system\b\|popen' "$ROOT/src" && bad "a shell call in src/" || ok "no_shell_call_in_src"
echo "MEASURED $names names tried"
[ $fails -eq 0 ]
