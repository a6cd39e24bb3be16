#!/usr/bin/env pybricks-micropython
"""Messaging between two bricks, the server: wait for the other brick, send it a greeting, await its answer.

Run it with its client, one robot each (the server is robot1, the client robot2):
    ev3sim2d run examples/pybricks/messaging_server.py examples/pybricks/messaging_client.py --maze empty
"""

from pybricks.messaging import BluetoothMailboxServer, NumericMailbox, TextMailbox

server = BluetoothMailboxServer()
greeting = TextMailbox("greeting", server)
number = NumericMailbox("number", server)

print("waiting for the client")
server.wait_for_connection()
print("connected")

greeting.send("hello!")
answer = number.wait_new()  # waits until the client sends a number
print("the client says", answer)
