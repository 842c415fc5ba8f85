#!/usr/bin/env bash
# A full disk ends a run cleanly: exit 3, a message naming the file, and
# the status file says 'failed', whatever the space left when the run
# starts (3000 to 8 KiB: the disk fills at a checkpoint, a field step or the
# set-up), on 1 and 2 ranks; never a crash or a hang.
# Needs a small file system of its own: a tmpfs (root); skipped otherwise.
#   full_disk.sh EXE
source "$(dirname "$0")/common.sh" "$1"
fs=$W/fs
mkdir -p "$fs"
if ! mount -t tmpfs -o size=4m udar_full_disk_test "$fs" 2>/dev/null; then
  echo "SKIP: cannot mount a tmpfs here (not root, or no mount permission)"; exit 0
fi
trap 'umount "$fs" 2>/dev/null; rm -rf "$W"' EXIT
case=taylor_ofhc_baseline
cp "$ROOT/tests/regression/$case/$case.msh" "$W/"
sed "s#^\( *\)directory = .*#\1directory = '$fs/out'#; s/^\( *\)t_end = .*/\1t_end = 30.0e-6/; s/^\( *\)dt_field = .*/\1dt_field = 2.0e-6, dt_checkpoint = 10.0e-6/" \
  "$ROOT/tests/regression/$case/$case.nml" > "$W/full.nml"
grep -q "directory = '$fs/out'" "$W/full.nml" || { bad "deck edit"; exit 1; }
for ranks in 1 2; do
  for left in 3000 2200 1700 1000 500 150 40 8; do
    rm -rf "${fs:?}"/*
    total=$(df -k --output=avail "$fs" | tail -1)
    fallocate -l $(( (total - left)*1024 )) "$fs/filler" 2>/dev/null || head -c $(( (total - left)*1024 )) /dev/zero > "$fs/filler"
    (cd "$W" && timeout 60 mpirun -np $ranks "$EXE" full.nml > run.log 2>&1); rc=$?
    st=$(sed -n 's/^status = //p' "$fs/out/$case.status" "$fs/out/full.status" 2>/dev/null | head -1)
    name="${ranks}_ranks_${left}_KiB_left"
    if [ $rc = 3 ] && [ "$st" = failed ] && ! grep -qiE 'segmentation|backtrace|signal 11' "$W/run.log" && \
       grep -qE "udar: error: .*(/out|could not be written|No space|cannot)" "$W/run.log"; then
      ok "$name: exit 3, status '${st:-none}': $(grep 'udar: error' "$W/run.log" | head -1 | cut -c1-100)"
    else
      bad "$name: exit $rc, status '${st:-none}'"; grep -vE '^ *$' "$W/run.log" | tail -8
    fi
  done
done
# a read-only file system: found by --check, at the deck line, before anything runs
rm -rf "${fs:?}"/*; mkdir -p "$fs/ro"
if mount -o remount,ro "$fs" 2>/dev/null; then
  (cd "$W" && "$EXE" --check full.nml > check.log 2>&1); rc=$?
  if [ $rc = 1 ] && grep -q "full.nml:[0-9]*: &output: directory = '$fs/out': cannot be created: this user cannot write into '$fs'" "$W/check.log"; then
    ok "read_only_file_system_found_by_check"
  else bad "read-only file system: --check exit $rc"; cat "$W/check.log"; fi
  mount -o remount,rw "$fs"
else echo "SKIP read-only remount"; fi
[ $fails -eq 0 ]
