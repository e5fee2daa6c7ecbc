/// <reference lib="dom" />
/**
 * The accessibility audit (issue 17): axe-core (`@axe-core/playwright`, every rule it runs by
 * default, none disabled) on the HUD against the real stack — a desktop, a phone and a tablet,
 * with the panels open — finds no violation.
 */
import AxeBuilder from '@axe-core/playwright';
import type { Page } from '@playwright/test';
import { expect, shot, test } from './fixtures.ts';

/** The violations axe finds on the page, one readable line each (rule, help, where). */
async function violations(page: Page): Promise<string[]> {
  const r = await new AxeBuilder({ page }).analyze();
  return r.violations.map(
    (v) =>
      `${v.id} (${v.impact}): ${v.help} — ${v.nodes.map((n) => n.target.join(' ')).join(', ')}`,
  );
}

/** Opens every folded panel and section (`<details>`) there is on screen. */
async function openFolded(page: Page): Promise<void> {
  const closed = page.locator('details:not([open]) > summary').filter({ visible: true });
  // an opened panel may reveal more folded sections inside it: open until none is left
  for (let i = 0; i < 40 && (await closed.count()) > 0; i++) await closed.first().click();
  await expect(closed).toHaveCount(0);
}

test.describe('accessibility audit: desktop', () => {
  test('no violations with the panels folded and open', async ({ hud: { page } }, testInfo) => {
    expect(await violations(page)).toEqual([]);
    await openFolded(page);
    expect(await violations(page)).toEqual([]);
    await shot(page, testInfo, 'a11y-desktop');
  });
});

test.describe('accessibility audit: phone 390×844', () => {
  test.use({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
  test('no violations with the sheet lowered and with each tab raised', async ({
    hud: { page },
  }, testInfo) => {
    // An axe run per tab: a budget of three minutes, not one (it took 1.2 min at load 28).
    test.slow();
    expect(await violations(page)).toEqual([]);
    const tabs = page.getByRole('navigation', { name: 'Panels' }).getByRole('button');
    for (const name of await tabs.allInnerTexts()) {
      const tab = tabs.filter({ hasText: name });
      await tab.tap();
      await expect(tab).toHaveAttribute('aria-expanded', 'true');
      await openFolded(page);
      expect(await violations(page), `with the ${name} tab raised`).toEqual([]);
    }
    await shot(page, testInfo, 'a11y-phone');
  });
});

test.describe('accessibility audit: tablet 1024×768', () => {
  test.use({ viewport: { width: 1024, height: 768 }, hasTouch: true });
  test('no violations with the panels open', async ({ hud: { page } }) => {
    expect(await violations(page)).toEqual([]);
    await openFolded(page);
    expect(await violations(page)).toEqual([]);
  });
});
