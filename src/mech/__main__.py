"""``python -m mech`` runs the command line (plain forms of the hot commands without click)."""

from mech.entry import main

if __name__ == "__main__":  # pragma: no cover
    main()
