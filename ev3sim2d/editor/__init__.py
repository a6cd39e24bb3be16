"""The world editor: a page in the browser, served on 127.0.0.1, that edits one world file."""
