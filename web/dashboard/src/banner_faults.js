// The faults in the AS banner, where the safety officer looks: how many, and the newest one's text (why the
// car is in Emergency, why it stopped), also on a phone where the fault list is far down the page.
export function showFaultsInBanner(el, faults) {
  el.hidden = faults.length === 0;
  if (!faults.length) {
    el.textContent = '';
    return;
  }
  const newest = faults[faults.length - 1];  // the list is oldest first
  const active = faults.filter((f) => f.active).length;
  const count = `${faults.length} fault${faults.length === 1 ? '' : 's'}${active < faults.length ? ` (${active} active)` : ''}`;
  el.textContent = `⚠ ${count}: ${newest.source}: ${newest.what}${newest.action ? ` → ${newest.action}` : ''}`;
  el.title = el.textContent;
}
