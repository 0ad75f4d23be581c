import sys

from dissector.app.cli import main

sys.exit(main())
