"""The brick process: what runs beside a student's program, isolated from the simulator (see docs/protocol.md)."""
