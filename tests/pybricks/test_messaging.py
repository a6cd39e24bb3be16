"""pybricks.messaging between the bricks of one world behaves as on EV3s with pybricks-micropython v2.0.0.

Sources (pybricks-micropython, tag v2.0.0): bricks/ev3dev/modules/pybricks/messaging.py (Mailbox and its
Logic/Numeric/TextMailbox encodings, MailboxHandlerMixIn: read_from_mailbox, send_to_mailbox and its
frame, wait_for_mailbox_update; BluetoothMailboxServer.wait_for_connection; BluetoothMailboxClient.connect
and close), bricks/ev3dev/modules/pybricks/bluetooth.py (RFCOMMServer.handle_request, server_close,
__exit__), bricks/ev3dev/modbluetooth.c (resolve: a paired device by alias or address, None otherwise).
The simulator's side is ev3sim2d/simulator/mailboxes.py.  Each test runs real programs, one per robot,
in one run (run_programs) and checks what they printed and when.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import textwrap

from ev3sim2d.simulator.mailboxes import CONNECT_US, LATENCY_US, MAILBOXES
from ev3sim2d.simulator.run import run_programs
from tests.inline_world import arena

TWO = "- {x_cm: 60, y_cm: 60, heading_deg: 0}\n  - {x_cm: 60, y_cm: 180, heading_deg: 0}"
THREE = TWO + "\n  - {x_cm: 180, y_cm: 120, heading_deg: 180}"
CONNECT_S = CONNECT_US / 1e6
LATENCY_S = LATENCY_US / 1e6

SERVER = """
    import time
    from pybricks.messaging import BluetoothMailboxServer, TextMailbox, NumericMailbox, LogicMailbox
    server = BluetoothMailboxServer()
    text = TextMailbox("greeting", server)
    number = NumericMailbox("distance", server)
    logic = LogicMailbox("ready", server)
    print("before", text.read(), number.read(), logic.read())
    server.wait_for_connection()
    print("connected", time.time())
    text.wait()
    print("text", repr(text.read()), time.time())
    text.send("hello to you!")
    print("number", number.wait_new())
    logic.wait()
    print("logic", logic.read())
    logic.wait()
    print("logic", logic.read())
"""

CLIENT = """
    import time
    from pybricks.messaging import BluetoothMailboxClient, TextMailbox, NumericMailbox, LogicMailbox
    client = BluetoothMailboxClient()
    text = TextMailbox("greeting", client)
    number = NumericMailbox("distance", client)
    logic = LogicMailbox("ready", client)
    started = time.time()
    client.connect("robot1")
    print("connected after {:.2f}".format(time.time() - started))
    sent = time.time()
    text.send("hello!")
    print("answer", repr(text.wait_new()), round(time.time() - sent, 3))
    number.send(12.5)
    time.sleep(0.1)
    logic.send(True)
    time.sleep(0.1)
    logic.send(False)
    time.sleep(0.1)
"""


def _run(tmp_path, *sources, start=TWO, time_limit_s=10):
    programs = []
    for i, source in enumerate(sources):
        path = tmp_path / f"robot{i + 1}.py"
        path.write_text(textwrap.dedent(source))
        programs.append(path)
    return run_programs(programs, arena(start=start), time_limit_s=time_limit_s, hang_after_s=5.0)


def _lines(result, robot: int) -> list[str]:
    return [o.text for o in result.trace.output if o.robot == robot]


def _times(result, robot: int) -> list[float]:
    return [o.t_s for o in result.trace.output if o.robot == robot]


def _finished(result) -> None:
    assert result.status == "finished", (result.reason, result.robots)
    assert all(r["status"] == "finished" for r in result.robots), result.robots


def test_a_server_and_a_client_exchange_text_numbers_and_booleans(tmp_path):
    """messaging.py: TextMailbox ('{}\\0', stripped of NUL), NumericMailbox (pack('<f')), LogicMailbox
    (one byte); Mailbox.read (None before any message), wait, wait_new; wait_for_connection and connect
    (messaging.py: BluetoothMailboxServer.wait_for_connection, BluetoothMailboxClient.connect)."""
    result = _run(tmp_path, SERVER, CLIENT)
    _finished(result)
    server, client = _lines(result, 0), _lines(result, 1)
    assert server[0] == "before None None None"
    assert server[1].startswith("connected")
    assert server[2].startswith("text 'hello!'")
    assert server[3:] == ["number 12.5", "logic True", "logic False"]
    assert client[0] == f"connected after {CONNECT_S:.2f}"
    answer, round_trip = client[1].rsplit(" ", 1)
    assert answer == "answer 'hello to you!'"
    # there and back: two Bluetooth trips, each a latency, plus the ticks the waits look in
    assert 2 * LATENCY_S <= float(round_trip) <= 2 * LATENCY_S + 0.05


def test_a_message_arrives_a_bluetooth_latency_after_it_is_sent(tmp_path):
    """messaging.py: MailboxHandlerMixIn.send_to_mailbox writes one frame to the RFCOMM socket;
    MailboxHandler.handle stores it when it arrives: here LATENCY_US of virtual time later."""
    sender = """
        import time
        from pybricks.messaging import BluetoothMailboxClient, NumericMailbox
        client = BluetoothMailboxClient()
        client.connect("robot1")
        box = NumericMailbox("t", client)
        time.sleep(0.5)
        print("sending")
        box.send(1)
        time.sleep(0.5)
    """
    receiver = """
        import time
        from pybricks.messaging import BluetoothMailboxServer, NumericMailbox
        server = BluetoothMailboxServer()
        server.wait_for_connection()
        box = NumericMailbox("t", server)
        box.wait()
        print("received", box.read())
    """
    result = _run(tmp_path, receiver, sender)
    _finished(result)
    assert _lines(result, 0) == ["received 1.0"]
    delay = _times(result, 0)[0] - _times(result, 1)[0]
    assert LATENCY_S <= delay <= LATENCY_S + 0.011  # (the wait looks once a tick)


def test_the_same_programs_give_the_same_run_every_time(tmp_path):
    """Lockstep (ev3sim2d/simulator/session.py, mailboxes.py): messages arrive at virtual times fixed by
    the programs alone, so two runs of the same programs have the same fingerprint and output."""
    chatty = """
        import time
        from pybricks.messaging import BluetoothMailboxServer, BluetoothMailboxClient, NumericMailbox
        from pybricks.messaging import TextMailbox
        me = {me}
        if me == 1:
            link = BluetoothMailboxServer()
            link.wait_for_connection()
        else:
            link = BluetoothMailboxClient()
            link.connect("robot1")
        box = NumericMailbox("n", link)
        seen = []
        for i in range(40):
            box.send(i * me)
            total = sum(range(1000 * (i % 7)))  # computing takes the brick's time, as on an EV3
            value = box.read()
            seen.append(value)
        print(me, seen)
        TextMailbox("done", link).send("bye")
        time.sleep(0.2)
    """
    runs = []
    for attempt in range(2):
        folder = tmp_path / str(attempt)
        folder.mkdir()
        result = _run(folder, chatty.format(me=1), chatty.format(me=2))
        _finished(result)
        runs.append((result.trace.fingerprint(), _lines(result, 0), _lines(result, 1)))
    assert runs[0] == runs[1]
    assert "None" in runs[0][1][0] and "2.0" in runs[0][1][0]  # (messages came in while it looped)


def test_connecting_to_a_name_no_brick_has_is_a_value_error_at_once(tmp_path):
    """modbluetooth.c: resolve returns None for a name no paired device has; messaging.py:
    BluetoothMailboxClient.connect then raises ValueError('no paired devices matching "..."'); a brick is
    not paired with itself, and a name that is not text is TypeError (mp_obj_str_get_str)."""
    client = """
        import time
        from pybricks.messaging import BluetoothMailboxClient
        client = BluetoothMailboxClient()
        for name in ("robot9", "robot2", "ROBOT1", 7):
            try:
                client.connect(name)
            except (ValueError, TypeError) as err:
                print(type(err).__name__, err)
    """
    result = _run(tmp_path, "import time\ntime.sleep(1)\n", client)
    _finished(result)
    assert _lines(result, 1)[:3] == [
        'ValueError no paired devices matching "robot9"',
        'ValueError no paired devices matching "robot2"',
        'ValueError no paired devices matching "ROBOT1"',
    ]
    assert _lines(result, 1)[3].startswith("TypeError")
    assert _times(result, 1)[2] < 0.1  # (at once: resolving asks no other brick)


def test_connecting_to_a_brick_that_does_not_listen_is_refused_after_the_connect(tmp_path):
    """bluetooth.py: RFCOMMClient.handle_request's socket.connect raises OSError (ECONNREFUSED) when the
    paired brick has no server on channel 1; messaging.py: connect forgets the failed connection, so a
    later connect to the same brick is tried again (and succeeds once that brick listens)."""
    late_server = """
        import time
        from pybricks.messaging import BluetoothMailboxServer
        time.sleep(2)
        server = BluetoothMailboxServer()
        server.wait_for_connection()
        print("accepted")
    """
    client = """
        import errno, time
        from pybricks.messaging import BluetoothMailboxClient
        client = BluetoothMailboxClient()
        try:
            client.connect("robot1")
        except OSError as err:
            print("refused", err.errno == errno.ECONNREFUSED)
        time.sleep(1.5)
        client.connect("robot1")
        print("connected")
    """
    result = _run(tmp_path, late_server, client)
    _finished(result)
    assert _lines(result, 1) == ["refused True", "connected"]
    refused, connected = _times(result, 1)
    assert CONNECT_S <= refused <= CONNECT_S + 0.01
    assert 2 * CONNECT_S + 1.5 <= connected <= 2 * CONNECT_S + 1.51
    assert _lines(result, 0) == ["accepted"]
    assert connected <= _times(result, 0)[0] <= connected + 0.011


def test_ev3dev_and_an_address_name_the_other_brick(tmp_path):
    """modbluetooth.c: resolve matches a paired device's alias (every EV3 is 'ev3dev' until renamed) or,
    ignoring case, its address; messaging.py: Mailbox.send(value, destination) sends to that brick only,
    and to a brick not connected raises KeyError (self._clients[addr])."""
    server = """
        from pybricks.messaging import BluetoothMailboxServer, TextMailbox
        server = BluetoothMailboxServer()
        server.wait_for_connection()
        box = TextMailbox("m", server)
        box.wait()
        print(box.read())
        try:
            box.send("x", "robot3")
        except KeyError as err:
            print("KeyError", err)
    """
    client = """
        from pybricks.messaging import BluetoothMailboxClient, TextMailbox
        client = BluetoothMailboxClient()
        client.connect("ev3dev")
        TextMailbox("m", client).send("via ev3dev", "00:16:53:00:00:01")
    """
    idle = "import time\ntime.sleep(3)\n"
    result = _run(tmp_path, server, client, idle, start=THREE)
    _finished(result)
    assert _lines(result, 0) == ["via ev3dev", "KeyError '00:16:53:00:00:03'"]


def test_a_raw_mailbox_sends_bytes_and_takes_encode_and_decode(tmp_path):
    """messaging.py: Mailbox keeps raw bytes unless given encode/decode functions; the value last
    delivered is what read() gives (one value per mailbox name); messages sent before the server accepts
    the connection wait in the socket and arrive once it does (MailboxHandler.handle reads them then)."""
    server = """
        import time
        from pybricks.messaging import BluetoothMailboxServer, Mailbox
        server = BluetoothMailboxServer()
        time.sleep(2)
        server.wait_for_connection()
        time.sleep(0.1)
        raw = Mailbox("raw", server)
        pair = Mailbox("pair", server, decode=lambda b: tuple(b))
        print(raw.read(), pair.read())
    """
    client = """
        import time
        from pybricks.messaging import BluetoothMailboxClient, Mailbox
        client = BluetoothMailboxClient()
        client.connect("robot1")
        Mailbox("raw", client).send(b"\\x00\\x01")
        Mailbox("raw", client).send(bytearray(b"last"))
        Mailbox("pair", client, encode=lambda p: bytes(p)).send((3, 4))
        time.sleep(2)
    """
    result = _run(tmp_path, server, client)
    _finished(result)
    assert _lines(result, 0) == ["b'last' (3, 4)"]


def test_a_message_too_large_for_a_frame_is_refused(tmp_path):
    """messaging.py: send_to_mailbox packs the frame's size in 16 bits and the name's in 8 ('<HHBBB...'),
    so no frame holds more than 65535 bytes; the firmware would send a garbled frame, here it is a
    ValueError; a program that goes round the shim to send one ends its own run only (mailboxes.py)."""
    client = """
        from pybricks.messaging import BluetoothMailboxClient, Mailbox, TextMailbox
        client = BluetoothMailboxClient()
        client.connect("robot1")
        for name, size in (("big", 65529), ("n" * 255, 1)):
            try:
                Mailbox(name, client).send(bytes(size))
            except ValueError as err:
                print("ValueError", len(name), size)
        Mailbox("fits", client).send(bytes(65535 - 7 - 5))
        TextMailbox("last", client).send("ok")
        print("sent")
        from pybricks import _link
        _link.call("mailbox", "send", 0, None, "big", "00" * 70000)
        print("never")
    """
    server = """
        import time
        from pybricks.messaging import BluetoothMailboxServer, Mailbox, TextMailbox
        server = BluetoothMailboxServer()
        server.wait_for_connection()
        TextMailbox("last", server).wait()
        print(len(Mailbox("fits", server).read()), TextMailbox("last", server).read())
        time.sleep(1)
        print("still running")
    """
    result = _run(tmp_path, server, client)
    assert _lines(result, 1) == ["ValueError 3 65529", "ValueError 255 1", "sent"]
    assert result.robots[1]["status"] != "finished"
    assert "mailbox message" in result.robots[1]["reason"]
    assert _lines(result, 0) == ["65523 ok", "still running"]


def test_a_brick_reaches_only_the_connection_objects_it_made(tmp_path):
    """messaging.py: a Mailbox reads its own connection object's mailboxes; here a brick that names a
    connection object it did not make (another brick's) ends its own run, and reads nothing."""
    server = """
        from pybricks.messaging import BluetoothMailboxServer, TextMailbox
        server = BluetoothMailboxServer()
        server.wait_for_connection()
        TextMailbox("secret", server).wait()
        print(TextMailbox("secret", server).read())
    """
    client = """
        import time
        from pybricks.messaging import BluetoothMailboxClient, TextMailbox
        client = BluetoothMailboxClient()
        client.connect("robot1")
        TextMailbox("secret", client).send("for robot1 only")
        time.sleep(0.5)
    """
    snoop = """
        import time
        time.sleep(0.5)
        from pybricks import _link
        print(_link.call("mailbox", "read", 0, "secret"))
    """
    result = _run(tmp_path, server, client, snoop, start=THREE)
    assert _lines(result, 0) == ["for robot1 only"]
    assert _lines(result, 2) == []
    assert result.robots[2]["status"] != "finished"
    assert result.robots[0]["status"] == result.robots[1]["status"] == "finished"


def test_waiting_for_a_message_that_never_comes_waits_until_the_time_limit(tmp_path):
    """messaging.py: wait_for_mailbox_update blocks on a lock until a message comes, and
    wait_for_connection on accept until a client connects: in virtual time here, so the run's time
    limit ends both, as it ends any waiting program."""
    server = """
        from pybricks.messaging import BluetoothMailboxServer
        BluetoothMailboxServer().wait_for_connection()
    """
    client = """
        from pybricks.messaging import BluetoothMailboxClient, TextMailbox
        client = BluetoothMailboxClient()
        TextMailbox("never", client).wait()
    """
    result = _run(tmp_path, server, client, time_limit_s=3)
    assert result.status == "time_limit", result.reason
    assert [r["status"] for r in result.robots] == ["time_limit", "time_limit"]


def test_the_server_has_server_close_and_no_close(tmp_path):
    """messaging.py: BluetoothMailboxServer defines no close() (its documentation's close is
    pybricks-api issue 51); bluetooth.py: RFCOMMServer.__exit__ calls server_close, which stops listening
    (a later connect is refused) while the connection accepted goes on; a second server while one
    listens cannot bind channel 1 (EADDRINUSE)."""
    server = """
        import time
        from pybricks.messaging import BluetoothMailboxServer, TextMailbox
        with BluetoothMailboxServer() as server:
            try:
                BluetoothMailboxServer()
            except OSError as err:
                print("second server", err.errno)
            server.wait_for_connection()
            try:
                server.close()
            except AttributeError:
                print("no close")
        box = TextMailbox("m", server)
        box.wait()
        print(box.read())
        server.wait_for_connection()
        print("accept on a closed server returns")
    """
    client = """
        import time
        from pybricks.messaging import BluetoothMailboxClient, TextMailbox
        with BluetoothMailboxClient() as client:
            client.connect("robot1")
            time.sleep(0.5)
            TextMailbox("m", client).send("still connected")
            try:
                BluetoothMailboxClient().connect("robot1")
            except OSError as err:
                print("refused", err.errno)
    """
    result = _run(tmp_path, server, client)
    _finished(result)
    assert _lines(result, 0) == [
        "second server 98",
        "no close",
        "still connected",
        "accept on a closed server returns",
    ]
    assert _lines(result, 1) == ["refused 111"]


def test_served_bricks_reach_each_other_as_in_one_run(tmp_path):
    """The same mailboxes through `ev3sim2d serve` and `ev3sim2d join` (each brick on a computer of its
    own, the session in the server): the run is the run of `ev3sim2d run` with both programs,
    fingerprint for fingerprint (messaging.py: wait_for_connection, connect, send, wait)."""
    (tmp_path / "server.py").write_text(textwrap.dedent(SERVER))
    (tmp_path / "client.py").write_text(textwrap.dedent(CLIENT))
    env = {**os.environ, "PYTHONHASHSEED": "0"}
    command = [sys.executable, "-m", "ev3sim2d"]
    world = ["--maze", "line-shared", "--time", "5"]
    subprocess.run(
        [*command, "run", "server.py", "client.py", *world, "--summary", "run.json", "--quiet"],
        cwd=tmp_path, env=env, check=True, capture_output=True, timeout=120,
    )  # fmt: skip
    served = subprocess.Popen(
        [*command, "serve", "--port", "0", "--robots", "2", *world, "--summary", "served.json"],
        cwd=tmp_path, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        port = re.search(r"serving .* on \S+:(\d+)", served.stderr.readline()).group(1)
        joins = [
            subprocess.Popen(
                [*command, "join", f"127.0.0.1:{port}", program, "--robot", robot],
                cwd=tmp_path,
                env=env,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )  # fmt: skip
            for program, robot in (("client.py", "2"), ("server.py", "1"))
        ]
        done = [join.communicate(timeout=120) for join in joins]
        assert [join.returncode for join in joins] == [0, 0], done
        served.communicate(timeout=120)
    finally:
        served.kill()
        served.wait()
    ran = json.loads((tmp_path / "run.json").read_text())
    joined = json.loads((tmp_path / "served.json").read_text())
    assert joined["fingerprint"] == ran["fingerprint"]
    assert joined["output"] == ran["output"]
    assert "text 'hello!'" in " ".join(ran["output"])


def test_a_connection_keeps_a_bounded_number_of_mailboxes(tmp_path):
    """messaging.py: MailboxHandler.handle keeps the latest data of every mailbox name in a dict with no
    bound; here a connection object keeps MAILBOXES names (mailboxes.py), and messages to more are lost,
    so a program cannot fill the simulator's memory."""
    server = f"""
        import time
        from pybricks.messaging import BluetoothMailboxServer, TextMailbox
        server = BluetoothMailboxServer()
        server.wait_for_connection()
        TextMailbox("0", server).wait()
        time.sleep(1)
        print(TextMailbox("0", server).read(), TextMailbox("{MAILBOXES - 1}", server).read(),
              TextMailbox("{MAILBOXES}", server).read(), TextMailbox("last", server).read())
    """
    client = f"""
        from pybricks.messaging import BluetoothMailboxClient, TextMailbox
        client = BluetoothMailboxClient()
        client.connect("robot1")
        for i in range({MAILBOXES} - 1):
            TextMailbox(str(i), client).send(i)
        TextMailbox(str({MAILBOXES} - 1), client).send("full")
        TextMailbox("0", client).send("again")
        TextMailbox("{MAILBOXES}", client).send("lost")
        TextMailbox("last", client).send("lost too")
    """
    result = _run(tmp_path, server, client, time_limit_s=5)
    _finished(result)
    assert _lines(result, 0) == ["again full None None"]


def test_sending_over_a_connection_the_other_brick_closed_is_an_oserror(tmp_path):
    """messaging.py: BluetoothMailboxClient.close closes its sockets; the server keeps the connection
    in its _clients, and its next send_to_mailbox writes to a socket whose other end is gone: OSError
    (ENOTCONN), once the close has crossed (a Bluetooth trip)."""
    server = """
        import time
        from pybricks.messaging import BluetoothMailboxServer, TextMailbox
        server = BluetoothMailboxServer()
        server.wait_for_connection()
        box = TextMailbox("m", server)
        box.wait()
        box.send("fine")
        time.sleep(0.5)
        try:
            box.send("anyone?")
        except OSError as err:
            print("OSError", err.errno)
    """
    client = """
        import time
        from pybricks.messaging import BluetoothMailboxClient, TextMailbox
        with BluetoothMailboxClient() as client:
            client.connect("robot1")
            box = TextMailbox("m", client)
            box.send("hi")
            print(box.wait_new())
        print(box.read())
        time.sleep(1)
    """
    result = _run(tmp_path, server, client)
    _finished(result)
    assert _lines(result, 0) == ["OSError 107"]
    assert _lines(result, 1) == ["fine", "fine"]
