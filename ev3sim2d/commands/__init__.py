"""The subcommands of `ev3sim2d`, one module each (NAME, HELP, add_arguments, main)."""
