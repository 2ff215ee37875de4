"""The shared task board as a service (§3.4.3; the ``server`` extra): a FastAPI app
(:func:`supportive.service.app.create_app`), its store (SQLAlchemy: SQLite or PostgreSQL), the live event hub,
the lab screen's static page and the launcher behind ``supportive serve``. Import from the modules; this
package imports nothing, so that it loads without the extra."""
