# Counts the multiply-add instructions of named functions in `objdump -d --no-show-raw-insn
# -C` output of an aarch64 binary (bench/neon/check.sh runs it; see bench/README.md).
#
# `names` holds ;-separated name tails, each optionally followed by =N: the function
# (every instance whose demangled name ends so; a generic one has one per precision, told
# apart by its floating-point registers) must have a fused multiply-add (vector fmla/fmls or
# scalar fmadd/fmsub/fnmadd/fnmsub) inside a loop, and at least N vector ones there. A loop
# is the address range from a backward branch's target to the branch; a function with no
# loop (its loops unrolled) counts whole. Prints a Markdown
# table row per instance and exits 1 when a name matches nothing or an instance falls short.
function flush(   i, j, a, op, arg, inloop, vfma, sfma, vmul, smul, dregs, sregs, status) {
  if (current == "") return
  vfma = sfma = vmul = smul = dregs = sregs = 0
  for (i = 1; i <= count; i++) {
    op = ops[i]
    arg = args[i]
    # A function without loops (fully unrolled) counts whole.
    inloop = (loops == 0)
    for (j = 1; j <= loops; j++) {
      if (addr[i] >= lo[j] && addr[i] <= hi[j]) { inloop = 1; break }
    }
    if (op ~ /^f(mla|mls)$/) vfma += inloop
    else if (op ~ /^fn?m(add|sub)$/) sfma += inloop
    else if (op == "fmul" && arg ~ /^v/) vmul += inloop
    else if (op == "fmul") smul += inloop
    if (op ~ /^f/ && (arg ~ /^d[0-9]/ || arg ~ /\.2d/)) dregs++
    if (op ~ /^f/ && (arg ~ /^s[0-9]/ || arg ~ /\.[24]s/)) sregs++
  }
  status = "ok"
  if (vfma + sfma == 0 || vfma < want[current]) { status = "MISSING"; failed = 1 }
  printf "| `%s` | %s%s | %d | %d | %d | %d | %s |\n", current, (dregs >= sregs) ? "f64" : "f32", \
    (loops == 0) ? ", unrolled" : "", vfma, sfma, vmul, smul, status
  seen[current] = 1
  current = ""
}
# The value of hexadecimal digits `h` (mawk has no strtonum).
function hex(h,   v, i) {
  v = 0
  for (i = 1; i <= length(h); i++) v = 16 * v + index("0123456789abcdef", substr(h, i, 1)) - 1
  return v
}
BEGIN {
  n = split(names, list, ";")
  for (i = 1; i <= n; i++) {
    split(list[i], kv, "=")
    pattern[i] = kv[1]
    want[kv[1]] = kv[2] + 0
  }
  print "| function (in loops) | precision | vector fmla/fmls | scalar fmadd/fmsub | vector fmul | scalar fmul | |"
  print "|---|---|---|---|---|---|---|"
}
/^[0-9a-f]+ <.*>:$/ {
  flush()
  name = $0
  sub(/^[0-9a-f]+ </, "", name)
  sub(/>:$/, "", name)
  for (i = 1; i <= n; i++) {
    if (substr(name, length(name) - length(pattern[i]) + 1) == pattern[i]) {
      current = pattern[i]
      count = loops = 0
    }
  }
  next
}
current != "" && /^ +[0-9a-f]+:\t/ {
  a = $1
  sub(/:$/, "", a)
  count++
  addr[count] = hex(a)
  ops[count] = $2
  args[count] = $3
  # A branch to a lower address in this function closes a loop.
  if ($2 ~ /^(b(\..*)?|cbn?z|tbn?z)$/ && match($0, /\t[0-9a-f]+ </)) {
    target = hex(substr($0, RSTART + 1, RLENGTH - 3))
    if (target < addr[count]) { loops++; lo[loops] = target; hi[loops] = addr[count] }
  }
}
END {
  flush()
  for (i = 1; i <= n; i++) {
    if (!(pattern[i] in seen)) {
      printf "| `%s` | - | not found | | | | MISSING |\n", pattern[i]
      failed = 1
    }
  }
  exit failed
}
