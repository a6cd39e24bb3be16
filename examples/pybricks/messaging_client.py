#!/usr/bin/env pybricks-micropython
"""Messaging between two bricks, the client: connect to the server brick, read its greeting, answer it.

Run it with the server: see examples/pybricks/messaging_server.py.
"""

from pybricks.messaging import BluetoothMailboxClient, NumericMailbox, TextMailbox

SERVER = "robot1"  # the server brick's name (on real EV3s: the name its screen shows, e.g. "ev3dev")

client = BluetoothMailboxClient()
greeting = TextMailbox("greeting", client)
number = NumericMailbox("number", client)

print("connecting to", SERVER)
client.connect(SERVER)
print("connected")

greeting.wait()
print("the server says", greeting.read())
number.send(42)
