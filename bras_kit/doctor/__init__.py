"""``bras-kit doctor``: what this machine has (the install checks)."""
