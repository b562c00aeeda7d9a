"""What a stranger's file or code meets first: the reader that stays beneath a folder, the gates
for terminal text, CSV cells, file names and YAML, the scratch folders, the sandbox and the
containment of learner code. Above ``core`` only."""
