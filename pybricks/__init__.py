"""Pybricks 2.0 for the LEGO MINDSTORMS EV3 (LEGO Education's "EV3 MicroPython"), as ev3sim2d runs it.

Module for module the layout of the firmware's `pybricks` package (pybricks-micropython v2.0.0,
bricks/ev3dev/modules/pybricks and extmod/): hubs, ev3devices, nxtdevices, iodevices, parameters,
tools, robotics, media.ev3dev, messaging, and the 1.0 compatibility module ev3brick.  Every device is
reached through pybricks._link, the one module that talks to the simulated brick; the devices are the
same simulated ones the ev3dev2 shim drives.  Importing the shim works anywhere; using a device works
only inside a simulated run.
"""
