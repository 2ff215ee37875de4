"""The board service's routers: the board and its operations, and live updates."""
