"""Findings as data: the rule registry every rule family registers in, the finding records and
the reports that word them."""
