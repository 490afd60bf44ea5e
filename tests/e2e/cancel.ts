// The demo page's Cancel, shared by the page and threads tests.
import type { Page } from 'playwright-core';
import { expect } from 'vitest';

/** Start a remesh that lasts seconds (fandisk at the page's 2 % can end before a click lands),
 *  cancel it from the button, and check the page is back to its loaded model with the notice;
 *  the edge length is put back. */
export async function cancelLongRemesh(page: Page): Promise<void> {
  const edge = page.locator('.lil-controller', { hasText: 'edge length' }).locator('input').first();
  const defaultEdge = await edge.inputValue();
  await edge.fill('0.002');
  await edge.press('Enter');
  await page.click('[data-testid=remesh]');
  await page.waitForFunction(() => document.body.dataset.state === 'remeshing', undefined, { timeout: 10_000 });
  await page.click('[data-testid=cancel]');
  await page.waitForFunction(() => ['loaded', 'error', 'remeshed'].includes(document.body.dataset.state ?? ''), undefined, { timeout: 20_000 });
  expect(await page.evaluate(() => document.body.dataset.state)).toBe('loaded');
  expect(await page.textContent('[data-testid=notice]')).toMatch(/cancelled/i);
  await edge.fill(defaultEdge);
  await edge.press('Enter');
}
