"""Messages between EV3 bricks over Bluetooth (pybricks.messaging, Pybricks 2.0).

As pybricks-micropython v2.0.0 defines them (bricks/ev3dev/modules/pybricks/messaging.py, on top of
bricks/ev3dev/modules/pybricks/bluetooth.py): a BluetoothMailboxServer listens for clients, a
BluetoothMailboxClient connects to servers by brick name or address, and each keeps the latest value
delivered to every mailbox name.  Mailboxes encode values as the standard EV3 firmware's message
blocks do: text with a final NUL, a 32-bit little-endian float, one byte for a logic value.

Here the other bricks are the other robots of the simulated world: a brick's name is its robot's
name (`robot1`, `robot2`, ...), every brick also answers to `ev3dev` (the name every EV3 has until
renamed: it means the first other robot), and to its address (00:16:53:00:00:01 for robot1).
Connections and messages travel through the simulator in virtual time (ev3sim2d/simulator/
mailboxes.py): a message arrives about 20 ms after it is sent, a connect takes 1 s, and every wait
(wait(), wait_new(), wait_for_connection(), connect()) waits in virtual time, until the run's time
limit if nothing comes.
"""

import math
import os
import time
from struct import error as _struct_error
from struct import pack, unpack

from . import _link

# EV3 standard firmware is hard-coded to use channel 1 (messaging.py)
EV3_RFCOMM_CHANNEL = 1

# EV3 VM bytecodes of a mailbox message (messaging.py)
SYSTEM_COMMAND_NO_REPLY = 0x81
WRITEMAILBOX = 0x9E

FRAME_BYTES = 65535  # the frame's 16-bit size field: a message, its name and 7 bytes of header
NAME_BYTES = 255  # the name's 8-bit size field, its final NUL counted


def _ask(*request, brick=None):
    """A request to the simulated Bluetooth: its answer, or the exception the firmware would raise."""
    answer = _link.call("mailbox", *request)
    if type(answer) is list and answer and answer[0] in ("OSError", "ValueError", "KeyError"):
        kind = answer[0]
        if kind == "OSError":
            raise OSError(answer[1], os.strerror(answer[1]))
        if kind == "KeyError":
            raise KeyError(answer[1])
        if answer[1] == "no paired devices matching":  # (bluetooth_c.resolve found no such brick)
            raise ValueError(f'no paired devices matching "{brick}"')
        raise ValueError(answer[1])
    return answer


def _wire_bytes(value, size):
    """What MicroPython's pack('{size}s', value) puts on the wire: the bytes of value (a text's UTF-8),
    cut to size or padded with NUL."""
    data = value.encode() if isinstance(value, str) else bytes(value)
    return data[:size] + bytes(max(0, size - len(data)))


class Mailbox:
    def __init__(self, name, connection, encode=None, decode=None):
        """Object that represents a mailbox for sending and receiving messages from other connected
        devices (messaging.py: Mailbox).

        Arguments:
            name (str): The name of this mailbox.
            connection: A BluetoothMailboxServer or BluetoothMailboxClient.
            encode: A function that encodes an object into a bytes-like object.
            decode: A function that decodes an object from a bytes-like object.
        """
        self.name = name
        self._connection = connection
        if encode:
            self.encode = encode
        if decode:
            self.decode = decode

    def encode(self, value):
        return value

    def decode(self, payload):
        return payload

    def read(self):
        """The decoded current value of the mailbox, or None if it never received one."""
        data = self._connection.read_from_mailbox(self.name)
        if data is None:
            return None
        return self.decode(data)

    def send(self, value, destination=None):
        """Sends a value to the mailboxes of this name on the connected devices (destination None),
        or on the one named (a brick's name or address)."""
        data = self.encode(value)
        self._connection.send_to_mailbox(destination, self.name, data)

    def wait(self):
        """Waits for the mailbox to receive a message (the next one from now)."""
        self._connection.wait_for_mailbox_update(self.name)

    def wait_new(self):
        """Waits for a message that differs from the mailbox's current value; returns it (as read())."""
        old = self.read()
        while True:
            self.wait()
            new = self.read()
            if new != old:
                return new


class LogicMailbox(Mailbox):
    """Mailbox that holds a logic or boolean value, as the standard firmware's "logic" message blocks."""

    def encode(self, value):
        return b"\x01" if value else b"\x00"

    def decode(self, payload):
        return bool(payload[0])


class NumericMailbox(Mailbox):
    """Mailbox that holds a number, as a 32-bit float (the standard firmware's "numeric" message blocks)."""

    def encode(self, value):
        try:
            return pack("<f", value)
        except OverflowError:  # (MicroPython packs a float too large for 32 bits as infinity)
            return pack("<f", math.copysign(math.inf, value))
        except _struct_error:
            raise TypeError(f"can't convert {type(value).__name__} to float") from None

    def decode(self, payload):
        return unpack("<f", payload)[0]


class TextMailbox(Mailbox):
    """Mailbox that holds text, ended by a NUL (the standard firmware's "text" message blocks)."""

    def encode(self, value):
        return f"{value}\0"

    def decode(self, payload):
        return payload.decode().strip("\0")


class MailboxHandlerMixIn:
    """What a server and a client share: the mailboxes their connections deliver to, and sending."""

    def __init__(self):
        self._clients = {}  # address -> True, for each connection, in the order they were made
        self._endpoint = None  # this object's number in the simulated Bluetooth

    def read_from_mailbox(self, mbox):
        """The raw data last delivered to the mailbox, or None if nothing ever was."""
        if not isinstance(mbox, str) or self._endpoint is None:
            return None
        _, data = _ask("read", self._endpoint, mbox)
        return None if data is None else bytes.fromhex(data)

    def send_to_mailbox(self, brick, mbox, payload):
        """Sends raw data to a mailbox of every connected device (brick None) or of the brick named."""
        mbox_len = len(mbox) + 1
        payload_len = len(payload)
        send_len = 7 + mbox_len + payload_len
        if mbox_len > NAME_BYTES or send_len > FRAME_BYTES:
            raise ValueError(
                "mailbox message too long: its name is 254 bytes at most, and the name and the value "
                "together 65527 (the frame's 16-bit size)"
            )
        if brick is not None and not isinstance(brick, str):
            raise TypeError(f"can't convert {type(brick).__name__} to str")
        name = _wire_bytes(mbox, mbox_len)
        data = _wire_bytes(payload, payload_len)
        try:
            received_as = name.decode().strip("\0")
        except UnicodeError:
            return  # (the receiving brick could not read the name: it would stop listening)
        if self._endpoint is None:
            return
        answer = _ask("send", self._endpoint, brick, received_as, data.hex(), brick=brick)
        if answer[1] > 0:
            time.sleep(answer[1] / 1e6)  # (the socket's buffer is full: send waits for room)

    def wait_for_mailbox_update(self, mbox):
        """Waits until mbox receives a value."""
        while not isinstance(mbox, str) or self._endpoint is None:
            time.sleep(1)  # (no message can ever be delivered to it: wait as the firmware does)
        seen, _ = _ask("read", self._endpoint, mbox)
        _ask("until", "read", self._endpoint, mbox, seen)


class BluetoothMailboxServer(MailboxHandlerMixIn):
    def __init__(self):
        """Object that represents incoming Bluetooth connections from other EV3s (it listens on RFCOMM
        channel 1 from now on: a second server at the same time is OSError EADDRINUSE)."""
        super().__init__()
        self._endpoint = _ask("server")[1]

    def __enter__(self):
        return self

    def __exit__(self, type, value, traceback):
        self.server_close()

    def wait_for_connection(self, count=1):
        """Waits for `count` BluetoothMailboxClients on remote devices to connect."""
        for _ in range(count):
            self.handle_request()

    def handle_request(self):
        """Accepts one connection (returns at once on a server that is closed, as its accept fails)."""
        answer = _ask("until", "accept", self._endpoint)
        if answer[0] == "ok":
            self._clients[answer[1]] = True

    def server_close(self):
        """Stops listening; the connections accepted stay open (bluetooth.py: RFCOMMServer.server_close).
        The firmware's server has no close(), whatever its documentation says."""
        _ask("server_close", self._endpoint)


class BluetoothMailboxClient(MailboxHandlerMixIn):
    """Object that represents outgoing Bluetooth connections to one or more remote EV3s."""

    def __init__(self):
        super().__init__()
        self._endpoint = _ask("client")[1]

    def __enter__(self):
        return self

    def __exit__(self, type, value, traceback):
        self.close()

    def connect(self, brick):
        """Connects to a BluetoothMailboxServer on another brick, by its name or address.

        Raises TypeError (brick is not text), ValueError (no paired brick of that name, or a connection
        to it exists already), OSError (ECONNREFUSED: the brick does not listen)."""
        if not isinstance(brick, str):
            raise TypeError(f"can't convert {type(brick).__name__} to str")
        _, wait_us, addr = _ask("connect", self._endpoint, brick, brick=brick)
        time.sleep(wait_us / 1e6)  # (paging the other brick, then RFCOMM)
        _ask("until", "connected", self._endpoint, addr)
        self._clients[addr] = True

    def close(self):
        """Closes the connections."""
        _ask("close", self._endpoint)
        self._clients.clear()


__all__ = [
    "Mailbox",
    "LogicMailbox",
    "NumericMailbox",
    "TextMailbox",
    "BluetoothMailboxServer",
    "BluetoothMailboxClient",
]
