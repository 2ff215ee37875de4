"""``python -m supportive.cli``: the ``supportive`` command."""

from supportive.cli.app import main

main()
