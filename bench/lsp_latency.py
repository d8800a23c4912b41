#!/usr/bin/env python3
"""Latency of `radc lsp`, driven over stdio as an editor drives it.

Writes a scene of N primitives that uses a function file (`f.cal`, through a
`brightfunc`) into a temporary folder, opens both, then:
  - open -> first diagnostics of the scene;
  - E one-character edits of the scene (a digit of one radius changes), each timed
    from `didChange` to the `publishDiagnostics` of that version; sent as the
    server asks (incremental range edits when it offers them, else the full text);
    then E edits typing and erasing a digit (later spans move), and E typing and
    erasing a letter in the number (the statement breaks, then mends);
  - H hovers and H completions, each timed from request to response;
  - the server's memory (VmRSS and peak VmHWM from /proc);
  - the server's parse counters (`radc/stats`, enabled by RADC_LSP_STATS=1) before
    and after the edits: the scene is re-parsed once per edit (only the statement
    the edit touched is read again: whole parses and statements read are counted
    too), the .cal never.

usage: bench/lsp_latency.py [path/to/radc] [primitives] [edits]
Figures and the command are in BENCHMARKS.md (language server latency).
"""
import json, os, statistics, subprocess, sys, tempfile, time

radc = sys.argv[1] if len(sys.argv) > 1 else "target/release/radc"
n = int(sys.argv[2]) if len(sys.argv) > 2 else 50000
edits = int(sys.argv[3]) if len(sys.argv) > 3 else 20
hovers = 20

CAL = "k : 2 * 3;\nscale(x) = x * k;\nrefl = scale(Dx) * .1 + .5;\n"
HEAD = "void brightfunc shade\n2 refl f.cal\n0\n0\n\n"


def scene():
    parts = [HEAD]
    parts += [f"shade plastic m{i}\n0\n0\n5 .5 .5 .5 0 0\n" for i in range(50)]
    for i in range(n):
        parts.append(f"m{i % 50} sphere s{i}\n0\n0\n4 {i} 0 0 1.5\n")
    return "".join(parts)


folder = tempfile.mkdtemp(prefix="lsp-latency-")
with open(os.path.join(folder, "f.cal"), "w") as f:
    f.write(CAL)
text = scene()
with open(os.path.join(folder, "scene.rad"), "w") as f:
    f.write(text)
scene_uri = "file://" + os.path.join(folder, "scene.rad")
cal_uri = "file://" + os.path.join(folder, "f.cal")

env = dict(os.environ, RADC_LSP_STATS="1")
p = subprocess.Popen([radc, "lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, env=env)
next_id = [100]


def send(msg):
    body = json.dumps(msg).encode()
    p.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
    p.stdin.flush()


def recv():
    length = 0
    while True:
        line = p.stdout.readline().strip()
        if not line:
            break
        if line.startswith(b"Content-Length:"):
            length = int(line.split(b":")[1])
    return json.loads(p.stdout.read(length))


def wait(pred):
    while True:
        m = recv()
        if pred(m):
            return m


def request(method, params):
    next_id[0] += 1
    i = next_id[0]
    send({"jsonrpc": "2.0", "id": i, "method": method, "params": params})
    return wait(lambda m: m.get("id") == i and "method" not in m).get("result")


def diagnostics_of(uri, version=None):
    return lambda m: (m.get("method") == "textDocument/publishDiagnostics"
                      and m["params"]["uri"] == uri
                      and (version is None or m["params"].get("version") == version))


def memory():
    fields = {}
    with open(f"/proc/{p.pid}/status") as f:
        for line in f:
            key, _, value = line.partition(":")
            if key in ("VmRSS", "VmHWM"):
                fields[key] = int(value.split()[0]) / 1024
    return fields


def cpu():
    """The server's CPU time so far (user + system), in seconds."""
    with open(f"/proc/{p.pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def ms(seconds):
    return 1000 * seconds


send({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {"capabilities": {}}})
init = wait(lambda m: m.get("id") == 1)
sync = init["result"]["capabilities"]["textDocumentSync"]["change"]
send({"jsonrpc": "2.0", "method": "initialized", "params": {}})
send({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {"textDocument": {
    "uri": cal_uri, "languageId": "calcomp", "version": 1, "text": CAL}}})
wait(diagnostics_of(cal_uri))
t = time.perf_counter()
send({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {"textDocument": {
    "uri": scene_uri, "languageId": "radiance", "version": 1, "text": text}}})
first = wait(diagnostics_of(scene_uri))
opened = ms(time.perf_counter() - t)
print(f"{n} primitives ({len(text) // 1024} KiB) using f.cal: open -> diagnostics {opened:.1f} ms "
      f"({len(first['params']['diagnostics'])} diagnostics); sync kind {sync}")
before = request("radc/stats", None)

# The radius "1.5" of sphere s{n//2}: its line, and the column of the digit "5".
target = n // 2
lines = text.split("\n")
line_no = lines.index(f"m{target % 50} sphere s{target}") + 3
column = len(lines[line_no]) - 1
version = [1]


def run_edits(label, count, edit):
    """Applies `count` edits, `edit(k)` giving (column, old length, new text) on the
    radius line; returns the wall times and the server CPU per edit."""
    times = []
    counts = set()
    cpu_before = cpu()
    for k in range(1, count + 1):
        col, old_len, new = edit(k)
        line = lines[line_no]
        lines[line_no] = line[:col] + new + line[col + old_len:]
        if sync == 2:
            change = {"range": {"start": {"line": line_no, "character": col},
                                "end": {"line": line_no, "character": col + old_len}}, "text": new}
        else:
            change = {"text": "\n".join(lines)}
        version[0] += 1
        t = time.perf_counter()
        send({"jsonrpc": "2.0", "method": "textDocument/didChange", "params": {
            "textDocument": {"uri": scene_uri, "version": version[0]}, "contentChanges": [change]}})
        published = wait(diagnostics_of(scene_uri, version[0]))
        times.append(ms(time.perf_counter() - t))
        counts.add(len(published["params"]["diagnostics"]))
    per_edit = ms(cpu() - cpu_before) / count
    print(f"edit -> diagnostics, {count} edits ({label}): median {statistics.median(times):.1f} ms, "
          f"worst {max(times):.1f} ms; server CPU {per_edit:.1f} ms per edit; "
          f"diagnostics published: {sorted(counts)}")
    return published


# One character replaced (the digit changes, no span moves).
run_edits("a digit replaced", edits, lambda k: (column, 1, str(k % 10)))
after = request("radc/stats", None)
# Typing: a digit inserted after the radius, then erased (every later span moves).
run_edits("a digit typed, then erased", edits,
          lambda k: (column + 1, 0, "7") if k % 2 else (column + 1, 1, ""))
# The statement broken (a letter in a number: the recovering parser reads the rest
# of the file, as a whole parse would), then mended.
run_edits("a letter typed into the number, then erased", edits,
          lambda k: (column + 1, 0, "x") if k % 2 else (column + 1, 1, ""))
last = request("radc/stats", None)


def timed(method, params):
    samples = []
    for _ in range(hovers):
        t = time.perf_counter()
        request(method, params)
        samples.append(ms(time.perf_counter() - t))
    return statistics.median(samples), max(samples)


where = {"textDocument": {"uri": scene_uri}, "position": {"line": line_no - 3, "character": 1}}
h = timed("textDocument/hover", where)
print(f"hover on a modifier of line {line_no - 2}: median {h[0]:.1f} ms, worst {h[1]:.1f} ms")
where = {"textDocument": {"uri": scene_uri}, "position": {"line": line_no + 1, "character": 0}}
c = timed("textDocument/completion", where)
print(f"completion after the last line of a primitive: median {c[0]:.1f} ms, worst {c[1]:.1f} ms")
where = {"textDocument": {"uri": cal_uri}, "position": {"line": 1, "character": 15}}
c = timed("textDocument/hover", where)
print(f"hover in f.cal: median {c[0]:.1f} ms, worst {c[1]:.1f} ms")

# As an editor asks while someone types: each request right after an edit (the
# first request after an edit is the one that finds the scope out of date).
for method, position in (("textDocument/hover", {"line": line_no - 3, "character": 1}),
                         ("textDocument/completion", {"line": line_no + 1, "character": 0})):
    samples = []
    for k in range(1, hovers + 1):
        col, old_len, new = column, 1, str(k % 10)
        lines[line_no] = lines[line_no][:col] + new + lines[line_no][col + old_len:]
        version[0] += 1
        send({"jsonrpc": "2.0", "method": "textDocument/didChange", "params": {
            "textDocument": {"uri": scene_uri, "version": version[0]}, "contentChanges": [
                {"range": {"start": {"line": line_no, "character": col},
                           "end": {"line": line_no, "character": col + old_len}}, "text": new}]}})
        wait(diagnostics_of(scene_uri, version[0]))
        t = time.perf_counter()
        request(method, {"textDocument": {"uri": scene_uri}, "position": position})
        samples.append(ms(time.perf_counter() - t))
    print(f"{method.split('/')[1]} right after an edit: median {statistics.median(samples):.1f} ms, "
          f"worst {max(samples):.1f} ms")
mem = memory()
print(f"server memory: {mem.get('VmRSS', 0):.0f} MB resident, peak {mem.get('VmHWM', 0):.0f} MB")
scene_path = os.path.realpath(os.path.join(folder, "scene.rad"))
cal_path = os.path.realpath(os.path.join(folder, "f.cal"))
print("radc/stats after the first edits:", json.dumps(after))
for name, path in (("scene.rad", scene_path), ("f.cal", cal_path)):
    def stat(stats, key):
        return (stats or {}).get(key, {}).get(path, 0)
    print(f"parses of {name}: {stat(before, 'parses')} after opening "
          f"({stat(before, 'whole_parses')} whole, {stat(before, 'statements_read')} statements read), "
          f"{stat(after, 'parses')} after the {edits} edits "
          f"({stat(after, 'whole_parses')} whole, {stat(after, 'statements_read')} statements read), "
          f"{stat(last, 'parses')} after all {3 * edits} "
          f"({stat(last, 'whole_parses')} whole, {stat(last, 'statements_read')} statements read)")

send({"jsonrpc": "2.0", "id": 2, "method": "shutdown"})
wait(lambda m: m.get("id") == 2)
send({"jsonrpc": "2.0", "method": "exit"})
p.wait(timeout=10)
