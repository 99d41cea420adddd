from canspec.cli import main

raise SystemExit(main())
