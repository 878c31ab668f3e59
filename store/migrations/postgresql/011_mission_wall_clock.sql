-- The wall-clock moments a mission started and ended, so a mission of an earlier
-- server session (whose station clock no longer maps to wall time) still shows when it ran.
-- NULL for every mission stored before.
ALTER TABLE missions ADD COLUMN started_utc TEXT;
ALTER TABLE missions ADD COLUMN ended_utc TEXT;
