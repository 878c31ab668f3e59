-- The server asks every second whether a vehicle's table changed: its newest ok turn.
CREATE INDEX turns_by_vehicle_status ON turns (vehicle_id, status, id);
