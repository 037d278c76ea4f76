from robodesc.cli import run

run()
