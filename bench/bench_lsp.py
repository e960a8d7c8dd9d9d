#!/usr/bin/env python3
"""Latency of `rulec lsp` on a large file: opens a generated rule file
(bench/rules/generate_rules.py), then makes EDITS one-character edits (a digit of a rule's
number, as typing does). For each edit it prints the time the server took to check the file
again (`$/tranche/stats`: parse the changed items, check, lint) and the round trip an editor
sees, from the didChange sent to its publishDiagnostics parsed (this includes writing and
parsing about 1 MB of JSON for the ~1100 diagnostics of 2000 rules). The limit the issue set,
100 ms for one edit of 2000 rules, is compared with the re-check. Timings grow with the load of
the machine: the table prints the load average, and the re-check's processor time (every thread
of the server), which a shared machine's load does not inflate much.
Usage: bench_lsp.py RULEC [RULES...] [--edits N]"""
import json, os, statistics, subprocess, sys, tempfile, time

args = [a for a in sys.argv[1:]]
edits = 30
if "--edits" in args:
    i = args.index("--edits"); edits = int(args[i + 1]); del args[i:i + 2]
rulec = args[0]
sizes = [int(a) for a in args[1:]] or [200, 2000, 10000]
here = os.path.dirname(os.path.abspath(__file__))
LIMIT_MS = 100.0


class Client:
    def __init__(self):
        self.p = subprocess.Popen([rulec, "lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.next_id = 0

    def send(self, method, params, request=False):
        m = {"jsonrpc": "2.0", "method": method, "params": params}
        if request:
            self.next_id += 1
            m["id"] = self.next_id
        b = json.dumps(m).encode()
        self.p.stdin.write(b"Content-Length: %d\r\n\r\n" % len(b) + b)
        self.p.stdin.flush()
        return m.get("id")

    def recv(self):
        n = None
        while True:
            line = self.p.stdout.readline()
            if not line:
                raise SystemExit("bench_lsp: the server closed its output")
            line = line.strip()
            if not line and n is not None:
                break
            if line.lower().startswith(b"content-length"):
                n = int(line.split(b":")[1])
        return json.loads(self.p.stdout.read(n))

    def wait_diagnostics(self, version):
        while True:
            m = self.recv()
            if m.get("method") == "textDocument/publishDiagnostics" and m["params"].get("version") == version:
                return m["params"]["diagnostics"]

    def request(self, method, params):
        i = self.send(method, params, True)
        while True:
            m = self.recv()
            if m.get("id") == i:
                return m.get("result")


print(f"load average: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
print("| rules | lines | open | re-check, median | re-check, p90 | re-check CPU, median | round trip, median | round trip, p90 | diagnostics | limit (re-check) |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
with tempfile.TemporaryDirectory() as work:
    for n in sizes:
        path = os.path.join(work, f"rules-{n}.rules")
        subprocess.run([sys.executable, os.path.join(here, "rules", "generate_rules.py"), str(n), path], check=True)
        text = open(path, encoding="utf-8").read()
        lines = text.split("\n")
        c = Client()
        c.request("initialize", {"capabilities": {}, "processId": None, "rootUri": None})
        c.send("initialized", {})
        uri = "file://" + path
        t0 = time.perf_counter()
        c.send("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "tranche-rules", "version": 1, "text": text}})
        diags = c.wait_diagnostics(1)
        opened = (time.perf_counter() - t0) * 1000
        # Edit the first digit of `speed = NN mm/s` on rule lines spread over the file.
        targets = [k for k, l in enumerate(lines) if "speed = " in l and l[l.index("speed = ") + 8].isdigit()]
        times, server, cpu = [], [], []
        for e in range(edits):
            k = targets[(e * 37) % len(targets)]
            col = lines[k].index("speed = ") + len("speed = ")
            digit = str((int(lines[k][col]) + 1) % 10 or 1)
            lines[k] = lines[k][:col] + digit + lines[k][col + 1:]
            change = {"range": {"start": {"line": k, "character": col}, "end": {"line": k, "character": col + 1}}, "text": digit}
            t0 = time.perf_counter()
            c.send("textDocument/didChange", {"textDocument": {"uri": uri, "version": e + 2}, "contentChanges": [change]})
            diags = c.wait_diagnostics(e + 2)
            times.append((time.perf_counter() - t0) * 1000)
            stats = c.request("$/tranche/stats", {})
            server.append(stats["lastAnalysisMs"])
            cpu.append(stats["lastAnalysisCpuMs"])
        c.request("shutdown", None)
        c.send("exit", None)
        c.p.wait()
        times.sort()
        server.sort()
        p90 = lambda v: v[max(0, int(len(v) * 0.9) - 1)]
        check = statistics.median(server)
        verdict = (f"{LIMIT_MS:.0f} ms: " + ("ok" if check < LIMIT_MS else "OVER")) if n == 2000 else ""
        print(f"| {n} | {len(lines)} | {opened:.0f} ms | {check:.1f} ms | {p90(server):.1f} ms | {statistics.median(cpu):.1f} ms | "
              f"{statistics.median(times):.1f} ms | {p90(times):.1f} ms | {len(diags)} | {verdict} |")
