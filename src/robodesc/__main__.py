import sys

from robodesc.cli import main

sys.exit(main())
