// How an operator counts a mission's turns, the same in every view: the turns done (ok) of the
// turns the plan holds. Live's event log said "turn 3/18" (its place among the ok turns) while
// Replay said "Turn 3 of 21" (its place among every stored attempt, aborted and rejected ones
// too), so one turn had two numbers. An attempt that did not count is an attempt at the next one.

/** The turns a mission's plan holds (its cells' `planned`); 0 without cells. */
export function plannedTurns(cells) {
  return (cells ?? []).reduce((n, c) => n + (c.planned ?? 1), 0);
}

/** "turn 3/18": the k-th ok turn of `planned` ("turn 3" when the plan is not known). */
export function turnLabel(k, planned) {
  return `turn ${k}${planned ? `/${planned}` : ''}`;
}

/** The label of a stored turn among the mission's (`rows` oldest first, as turn_list): "turn 3/18"
 *  for an ok one, "attempt at turn 4/18" for one that did not count. */
export function storedTurnLabel(rows, row, planned) {
  const before = rows.slice(0, Math.max(0, rows.indexOf(row))).filter((r) => r.status === 'ok').length;
  return row.status === 'ok' ? turnLabel(before + 1, planned) : `attempt at ${turnLabel(before + 1, planned)}`;
}
