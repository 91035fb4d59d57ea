"""The settings every layer shares: the one table of defaults and the thesis's reference case."""
