#!/usr/bin/env python3
"""Edit-to-diagnostics latency of `radc lsp`: opens a generated scene of N primitives,
then makes edits (one real changed per edit) and times each didChange until the
matching publishDiagnostics arrives. Prints the median and worst in milliseconds.

usage: bench/lsp_latency.py [path/to/radc] [primitives] [edits]

Measured Nov 2026 on the 2-core project machine, `cargo build --release`, full-text sync,
times including this script's JSON encoding:
  bench/lsp_latency.py target/release/radc 1000 30    open 3.3 ms, edit median 1.8 ms, worst 6.7 ms
  bench/lsp_latency.py target/release/radc 10000 30   open 34.5 ms, edit median 26.3 ms, worst 57.1 ms
"""
import json, subprocess, sys, time

radc = sys.argv[1] if len(sys.argv) > 1 else "target/release/radc"
n = int(sys.argv[2]) if len(sys.argv) > 2 else 10000
edits = int(sys.argv[3]) if len(sys.argv) > 3 else 30


def scene(k):
    parts = [f"void plastic m{i}\n0\n0\n5 .5 .5 .5 0 0\n" for i in range(50)]
    for i in range(n):
        parts.append(f"m{i % 50} sphere s{i}\n0\n0\n4 {i} 0 0 {1 + k / 1000}\n")
    return "".join(parts)


p = subprocess.Popen([radc, "lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE)


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


uri = "file:///tmp/latency.rad"
send({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {"capabilities": {}}})
wait(lambda m: m.get("id") == 1)
send({"jsonrpc": "2.0", "method": "initialized", "params": {}})
t = time.perf_counter()
send({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {"textDocument": {
    "uri": uri, "languageId": "radiance", "version": 1, "text": scene(0)}}})
wait(lambda m: m.get("method") == "textDocument/publishDiagnostics")
print(f"{n} primitives ({len(scene(0)) // 1024} KiB): open -> diagnostics {1000 * (time.perf_counter() - t):.1f} ms")
times = []
for k in range(1, edits + 1):
    text = scene(k)
    t = time.perf_counter()
    send({"jsonrpc": "2.0", "method": "textDocument/didChange", "params": {
        "textDocument": {"uri": uri, "version": k + 1}, "contentChanges": [{"text": text}]}})
    wait(lambda m: m.get("method") == "textDocument/publishDiagnostics"
         and m["params"].get("version") == k + 1)
    times.append(1000 * (time.perf_counter() - t))
times.sort()
print(f"edit -> diagnostics over {edits} edits: median {times[len(times) // 2]:.1f} ms, worst {times[-1]:.1f} ms")
send({"jsonrpc": "2.0", "id": 2, "method": "shutdown"})
wait(lambda m: m.get("id") == 2)
send({"jsonrpc": "2.0", "method": "exit"})
p.wait(timeout=10)
