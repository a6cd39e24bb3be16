"""ev3sim2d on systems without Linux's pieces, tried on Linux: Windows-like and macOS-like Pythons."""
