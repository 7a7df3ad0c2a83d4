"""``python -m mech`` runs the command line."""

from mech.cli import main

if __name__ == "__main__":  # pragma: no cover
    main()
