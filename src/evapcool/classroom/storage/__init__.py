"""The class server's store layer, one module per aggregate (classes, challenges, players,
entries) on a common base, the SQL store made of them, and its SQLite database; the
PostgreSQL one is pgstore.py, the interface and the names to import store.py."""
