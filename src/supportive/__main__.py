"""``python -m supportive``: the ``supportive`` program, started as its console script starts it
(:func:`supportive.launch.main`: Ctrl-C and SIGTERM taken care of before the command loads)."""

from supportive.launch import main

main()
