"""``python -m ship_gym.cli`` runs ``ship-gym``."""

from ship_gym.cli import main

raise SystemExit(main())
