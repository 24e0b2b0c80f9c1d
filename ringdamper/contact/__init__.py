"""Contact mechanics: static frictional contact solver and the 3-D friction element."""
